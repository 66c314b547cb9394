"""RRT-Connect's loop compiled (numba), for the sphere model: a run of iterations in one call.

The same search as `kitchen_tamp.motion.sampling.rrt_connect`, step for step: extend the growing
tree one step toward a sample, connect the other tree to the new node, swap. Nearest nodes are
found over the trees' arrays (each node's squared norm kept beside it), and every segment is
checked by the sphere model's compiled segment kernels (`sphere_segments`) on its
`ValidityArrays`, with no Python between them, in one `validity_scratch` per call (a failed step
is often one configuration, which costs less than allocating the kernel's buffers). Each
iteration draws its own sample, the iteration's of the seed's counter-based stream
(`counter_samples`, the same values the Python loop draws), so the same seed gives the same search.

The trees live in arrays passed back in each call: ``nodes`` (2, capacity, d), ``parents``
(2, capacity), ``squared_norms`` (2, capacity), and ``counters`` (see the ``COUNTER_`` indices).
`first_block` checks the ends and the straight line, makes the trees and runs the first block of
iterations; `rrt_connect_iterations` runs a further block. A call runs until its block of iterations
is done, the trees are joined, or the trees may not have room for another iteration; the caller
checks the clock, grows the arrays and calls again. Most queries end within the first call.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.segments import free_prefix_checked_in, segment_checked_in
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import (
    ValidityArrays,
    ValidityScratch,
    validity_scratch,
)
from kitchen_tamp.motion.sampling.configuration_tree import NO_PARENT
from kitchen_tamp.motion.sampling.counter_samples import GAMMA, MIX_FIRST, MIX_SECOND, UNIT

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

COUNTER_ITERATIONS = 0
"""Iterations run so far."""
COUNTER_GROWING = 1
"""Which tree (0: the start's, 1: the goal's) the next iteration extends."""
COUNTER_CHECKS = 2
"""Configurations checked so far (as `CountingSegmentChecker` counts them)."""
COUNTER_SIZES = 3
"""Nodes in tree 0 at this index, in tree 1 at the next."""
COUNTER_JOINED = 5
"""1 once the trees are joined: the start tree's end node at the next index, the goal tree's after."""
COUNTER_ROOM = 8
"""Rows an iteration may add to a tree (`room_per_iteration`): a call stops before an iteration
when a tree has fewer left, for the caller to grow the arrays."""
COUNTER_COUNT = 9

ENDS_JOINED, START_COLLIDES, GOAL_COLLIDES, LINE_BLOCKED = 0, 1, 2, 3
"""What `ends_and_line_checked` found: the straight line between the ends free, an end colliding,
or the ends valid and the line between them not."""


@numba.njit(cache=True)
def interval_count(q0: FloatArray, q1: FloatArray, resolution: float) -> int:
    """`kitchen_tamp.joint_spacing.interval_count` (the same sum as `joint_spacing.joint_distance`)."""
    return max(1, math.ceil(joint_distance(q0, q1) / resolution))


@numba.njit(cache=True)
def joint_distance(q0: FloatArray, q1: FloatArray) -> float:
    """`kitchen_tamp.joint_spacing.joint_distance`: the same sum, joint by joint in order."""
    squared = 0.0
    for j in range(q0.shape[0]):
        squared += (q1[j] - q0[j]) * (q1[j] - q0[j])
    return math.sqrt(squared)


@numba.njit(cache=True)
def room_per_iteration(lower: FloatArray, upper: FloatArray, step_size: float, resolution: float) -> int:
    """Rows an iteration may add to a tree: its connect's nodes across the whole box, and two."""
    resolutions_per_step = max(1, round(step_size / resolution))
    return 2 + math.ceil(joint_distance(lower, upper) / (resolutions_per_step * resolution))


@numba.njit(cache=True)
def _nearest(tree: int, q: FloatArray, nodes: FloatArray, squared_norms: FloatArray, size: int) -> int:
    """Index of the node of ``tree`` closest to ``q``: the smallest |x|^2 - 2 x.q."""
    best, best_key = 0, np.inf
    for i in range(size):
        dot = 0.0
        for j in range(q.shape[0]):
            dot += nodes[tree, i, j] * q[j]
        key = squared_norms[tree, i] - 2.0 * dot
        if key < best_key:
            best, best_key = i, key
    return best


@numba.njit(cache=True)
def _add(
    tree: int,
    q: FloatArray,
    parent: int,
    nodes: FloatArray,
    parents: IntArray,
    squared_norms: FloatArray,
    counters: IntArray,
) -> int:
    index: int = counters[COUNTER_SIZES + tree]
    squared = 0.0
    for j in range(q.shape[0]):
        nodes[tree, index, j] = q[j]
        squared += q[j] * q[j]
    parents[tree, index] = parent
    squared_norms[tree, index] = squared
    counters[COUNTER_SIZES + tree] = index + 1
    return index


@numba.njit(cache=True)
def _extend(
    tree: int,
    target: FloatArray,
    step_size: float,
    resolution: float,
    nodes: FloatArray,
    parents: IntArray,
    squared_norms: FloatArray,
    counters: IntArray,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> int:
    """One step from the nearest node toward ``target`` (`rrt_connect.extend_tree`): the new node's
    index, or -1 when the step collides."""
    near = _nearest(tree, target, nodes, squared_norms, counters[COUNTER_SIZES + tree])
    q_near = nodes[tree, near].copy()
    distance = joint_distance(q_near, target)
    q_new = target.copy() if distance <= step_size else q_near + (target - q_near) * (step_size / distance)
    intervals = interval_count(q_near, q_new, resolution)
    free, checked = segment_checked_in(q_near, q_new, intervals, False, True, arrays, margin, scratch)
    counters[COUNTER_CHECKS] += checked
    if not free:
        return -1
    return _add(tree, q_new, near, nodes, parents, squared_norms, counters)


@numba.njit(cache=True)
def _connect(
    tree: int,
    target: FloatArray,
    step_size: float,
    resolution: float,
    nodes: FloatArray,
    parents: IntArray,
    squared_norms: FloatArray,
    counters: IntArray,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[int, bool]:
    """Steps from the nearest node toward ``target`` until it is reached or a step collides
    (`rrt_connect.connect_tree`): the last node's index and whether it is ``target``."""
    near = _nearest(tree, target, nodes, squared_norms, counters[COUNTER_SIZES + tree])
    q_near = nodes[tree, near].copy()
    distance = joint_distance(q_near, target)
    if distance == 0.0:
        return near, True
    resolutions_per_step = max(1, round(step_size / resolution))
    free_length, checked = free_prefix_checked_in(
        q_near, target, distance, resolution, resolutions_per_step, arrays, margin, scratch
    )
    counters[COUNTER_CHECKS] += checked
    reached = free_length >= distance
    if reached:
        steps = math.ceil(distance / (resolutions_per_step * resolution)) - 1
    else:
        steps = round(free_length / resolution) // resolutions_per_step
    index = near
    for step in range(1, steps + 1):
        along = (step * resolutions_per_step) * resolution
        q = q_near + (along / distance) * (target - q_near)
        index = _add(tree, q, index, nodes, parents, squared_norms, counters)
    if not reached:
        return index, False
    last = nodes[tree, index].copy()
    intervals = interval_count(last, target, resolution)
    free, checked = segment_checked_in(last, target, intervals, False, False, arrays, margin, scratch)
    counters[COUNTER_CHECKS] += checked
    if not free:
        return index, False
    return _add(tree, target, index, nodes, parents, squared_norms, counters), True


@numba.njit(cache=True, forceinline=True)
def sample_into(seed: int, index: int, lower: FloatArray, upper: FloatArray, out: FloatArray) -> None:
    """Sample ``index`` of the stream of ``seed`` (`counter_samples.counter_uniforms`' row) into
    ``out``, one SplitMix64 output a joint, without arrays (``uint64`` arithmetic wraps as numpy's)."""
    dimension = lower.shape[0]
    for j in range(dimension):
        bits = np.uint64(seed) + np.uint64(index * dimension + j + 1) * GAMMA
        bits = (bits ^ (bits >> np.uint64(30))) * MIX_FIRST
        bits = (bits ^ (bits >> np.uint64(27))) * MIX_SECOND
        bits = bits ^ (bits >> np.uint64(31))
        out[j] = lower[j] + (upper[j] - lower[j]) * (float(bits >> np.uint64(11)) * UNIT)


@numba.njit(cache=True)
def rrt_connect_iterations(
    seed: int,
    lower: FloatArray,
    upper: FloatArray,
    block: int,
    step_size: float,
    resolution: float,
    max_iterations: int,
    nodes: FloatArray,
    parents: IntArray,
    squared_norms: FloatArray,
    counters: IntArray,
    arrays: ValidityArrays,
    margin: float,
    tree_balance: float,
) -> int:
    """Run up to ``block`` iterations on the trees (the number run), iteration ``k`` toward sample
    ``k`` of the stream of ``seed`` in the box (lower, upper), stopping early when the trees are
    joined, at ``max_iterations``, or when either tree has fewer than ``COUNTER_ROOM`` free rows left.
    The trees take turns, except that with a positive ``tree_balance`` a tree more than that many
    times the other's size waits its turn."""
    capacity = nodes.shape[1]
    scratch = validity_scratch(arrays, nodes.shape[2])  # the validity kernel's buffers, for every check
    target = np.empty(lower.shape[0])  # each iteration's sample (`_extend` copies what it keeps)
    used = 0
    for _ in range(block):
        if counters[COUNTER_ITERATIONS] >= max_iterations:
            break
        if max(counters[COUNTER_SIZES], counters[COUNTER_SIZES + 1]) + counters[COUNTER_ROOM] > capacity:
            break
        used += 1
        sample_into(seed, counters[COUNTER_ITERATIONS], lower, upper, target)
        counters[COUNTER_ITERATIONS] += 1
        growing = counters[COUNTER_GROWING]
        other = 1 - growing
        new = _extend(
            growing,
            target,
            step_size,
            resolution,
            nodes,
            parents,
            squared_norms,
            counters,
            arrays,
            margin,
            scratch,
        )
        if new >= 0:
            reached_target = nodes[growing, new].copy()
            end, reached = _connect(
                other,
                reached_target,
                step_size,
                resolution,
                nodes,
                parents,
                squared_norms,
                counters,
                arrays,
                margin,
                scratch,
            )
            if reached:
                counters[COUNTER_JOINED] = 1
                counters[COUNTER_JOINED + 1 + growing] = new
                counters[COUNTER_JOINED + 1 + other] = end
                break
        if (
            tree_balance > 0.0
            and counters[COUNTER_SIZES + other] > tree_balance * counters[COUNTER_SIZES + growing]
        ):
            other = growing  # the other tree is the larger by more than the balance: grow this one again
        counters[COUNTER_GROWING] = other
    return used


@numba.njit(cache=True)
def joined_path(nodes: FloatArray, parents: IntArray, counters: IntArray) -> FloatArray:
    """The configurations from the start tree's root to its joined node, then the goal tree's from
    the node before its joined one (the same configuration) back to its root."""
    ends = (counters[COUNTER_JOINED + 1], counters[COUNTER_JOINED + 2])
    lengths = np.zeros(2, dtype=np.int64)
    for tree in range(2):
        index = ends[tree]
        while index != NO_PARENT:
            lengths[tree] += 1
            index = parents[tree, index]
    path = np.empty((lengths[0] + lengths[1] - 1, nodes.shape[2]))
    index = ends[0]
    for row in range(lengths[0] - 1, -1, -1):
        path[row] = nodes[0, index]
        index = parents[0, index]
    index = parents[1, ends[1]]
    for row in range(lengths[0], path.shape[0]):
        path[row] = nodes[1, index]
        index = parents[1, index]
    return path


@numba.njit(cache=True)
def ends_and_line_checked(
    start: FloatArray, goal: FloatArray, resolution: float, arrays: ValidityArrays, margin: float
) -> tuple[int, int]:
    """What a plan checks before its loop, in one call (from Python, each compiled call costs
    about 10 us): both ends, then (when both are valid) the straight line between them;
    (``ENDS_JOINED``, ``START_COLLIDES``, ``GOAL_COLLIDES`` or ``LINE_BLOCKED``, configurations
    checked, as `CountingSegmentChecker` counts them)."""
    scratch = validity_scratch(arrays, start.shape[0])
    ends = np.empty((2, start.shape[0]))
    ends[0], ends[1] = start, goal
    # Stopping at an invalid start leaves the goal unchecked, which the answer does not need; and the
    # segment checks pass True as well, so the loop compiles one copy of the kernel, not two (numba
    # specialises on the literal).
    valid = valid_rows(ends, arrays, margin, True, scratch)
    if not valid[0]:
        return START_COLLIDES, 2
    if not valid[1]:
        return GOAL_COLLIDES, 2
    intervals = interval_count(start, goal, resolution)
    free, checked = segment_checked_in(start, goal, intervals, False, False, arrays, margin, scratch)
    return (ENDS_JOINED if free else LINE_BLOCKED), 2 + checked


@numba.njit(cache=True)
def first_block(
    start: FloatArray,
    goal: FloatArray,
    seed: int,
    lower: FloatArray,
    upper: FloatArray,
    block: int,
    step_size: float,
    resolution: float,
    max_iterations: int,
    capacity: int,
    arrays: ValidityArrays,
    margin: float,
    tree_balance: float,
) -> tuple[int, int, FloatArray, FloatArray, IntArray, FloatArray, IntArray]:
    """A query's first call: `ends_and_line_checked`, then, when the straight line is blocked, the
    trees rooted at ``start`` (tree 0) and ``goal`` with ``capacity`` rows each and up to ``block``
    of `rrt_connect_iterations` on them. Returns what the ends and line found, the configurations
    they checked, the path (the ends when the line is free, the joined path when the trees were
    joined, else no rows), and the trees' ``nodes``, ``parents``, ``squared_norms`` and
    ``counters``, for further calls."""
    found, checked = ends_and_line_checked(start, goal, resolution, arrays, margin)
    dimension = start.shape[0]
    nodes = np.empty((2, capacity, dimension))
    parents = np.empty((2, capacity), dtype=np.int64)
    squared_norms = np.empty((2, capacity))
    counters = np.zeros(COUNTER_COUNT, dtype=np.int64)
    counters[COUNTER_ROOM] = room_per_iteration(lower, upper, step_size, resolution)
    _add(0, start, NO_PARENT, nodes, parents, squared_norms, counters)
    _add(1, goal, NO_PARENT, nodes, parents, squared_norms, counters)
    path = np.empty((0, dimension))
    if found == ENDS_JOINED:
        path = np.empty((2, dimension))
        path[0], path[1] = start, goal
    elif found == LINE_BLOCKED:
        rrt_connect_iterations(
            seed,
            lower,
            upper,
            block,
            step_size,
            resolution,
            max_iterations,
            nodes,
            parents,
            squared_norms,
            counters,
            arrays,
            margin,
            tree_balance,
        )
        if counters[COUNTER_JOINED]:
            path = joined_path(nodes, parents, counters)
    return found, checked, path, nodes, parents, squared_norms, counters
