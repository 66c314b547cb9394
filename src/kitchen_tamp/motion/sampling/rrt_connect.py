"""RRT-Connect: two trees, one from each end, alternately extended and connected."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from kitchen_tamp.joint_spacing import PLANNING_RESOLUTION_RAD
from kitchen_tamp.motion.collision_checker import CollisionChecker, JointConfiguration
from kitchen_tamp.motion.configuration_space import ConfigurationSpace
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.planning_result import (
    PlanningResult,
    PlanStatus,
    endpoint_collision_status,
)
from kitchen_tamp.motion.sampling.configuration_tree import ConfigurationTree
from kitchen_tamp.motion.sampling.counter_samples import CounterSamples, checked_seed
from kitchen_tamp.motion.sampling.rrt import steer
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker


@dataclass(frozen=True)
class RrtConnectHyperparameters:
    """Step (node spacing), edge-check resolution and iteration limit of `plan_rrt_connect`."""

    step_size: float = 1.0
    edge_resolution: float = PLANNING_RESOLUTION_RAD
    max_iterations: int = 10_000
    tree_balance: float = 0.0
    """0: the trees take turns. Positive (at least 1): after an iteration the other tree grows next
    unless it holds more than ``tree_balance`` times this tree's nodes, then this one grows again
    (a tree trapped near its end by a narrow passage is grown until it is out)."""
    clock: Callable[[], float] = time.perf_counter
    """What the time budget is measured on: wall seconds; ``time.process_time`` for CPU seconds."""

    def __post_init__(self) -> None:
        if self.step_size <= 0.0:
            raise ValueError(f"step_size must be positive, got {self.step_size}")
        if self.edge_resolution <= 0.0:
            raise ValueError(f"edge_resolution must be positive, got {self.edge_resolution}")
        if self.max_iterations < 1:
            raise ValueError(f"max_iterations must be at least 1, got {self.max_iterations}")
        if self.tree_balance != 0.0 and not self.tree_balance >= 1.0:
            raise ValueError(f"tree_balance must be 0 or at least 1, got {self.tree_balance}")


def extend_tree(
    tree: ConfigurationTree,
    target: JointConfiguration,
    segments: CountingSegmentChecker,
    step_size: float,
) -> int | None:
    """Take one step from the nearest node toward `target`; the new node's index or None."""
    near = tree.nearest(target)
    q_near = tree.node(near)
    q_new = steer(q_near, target, step_size)
    if not segments.segment_valid(q_near, q_new, check_start=False):
        return None
    return tree.add(q_new, near)


def connect_tree(
    tree: ConfigurationTree,
    target: JointConfiguration,
    segments: CountingSegmentChecker,
    step_size: float,
) -> tuple[int, bool]:
    """Step from the nearest node toward `target` until it is reached or a step collides.

    The straight line is checked from the near end at points exactly one
    resolution apart, a step (`step_size`, rounded to whole resolutions) at a
    time, each step's far end first, then its other points coarse to fine
    (`CountingSegmentChecker.free_prefix_length`); nodes are added at the
    end of every free step, so every new edge has been checked on the same
    points as its own segment check. The last, shorter edge into `target` is
    checked on its own. Returns the last node's index and whether it is
    `target` (valid, as the caller vouches).
    """
    near = tree.nearest(target)
    q_near = tree.node(near)
    distance = float(np.linalg.norm(target - q_near))
    if distance == 0.0:
        return near, True
    resolution = segments.resolution
    resolutions_per_step = max(1, round(step_size / resolution))
    free_length = segments.free_prefix_length(q_near, target, resolutions_per_step)
    reached = free_length >= distance
    if reached:
        steps = math.ceil(distance / (resolutions_per_step * resolution)) - 1
    else:
        steps = round(free_length / resolution) // resolutions_per_step
    index = near
    for step in range(1, steps + 1):
        along = (step * resolutions_per_step) * resolution
        index = tree.add(q_near + (along / distance) * (target - q_near), index)
    last_edge_free = reached and segments.segment_valid(
        tree.node(index), target, check_start=False, check_end=False
    )
    return (tree.add(target, index), True) if last_edge_free else (index, False)


def _joined_path(
    start_tree: ConfigurationTree, start_end: int, goal_tree: ConfigurationTree, goal_end: int
) -> JointPath:
    """Start-tree branch to its end node, then the goal-tree branch backwards (shared node once)."""
    from_start = start_tree.path_from_root(start_end)
    from_goal = goal_tree.path_from_root(goal_end)
    return np.concatenate([from_start, from_goal[-2::-1]])


def plan_rrt_connect(
    start: npt.ArrayLike,
    goal: npt.ArrayLike,
    space: ConfigurationSpace,
    checker: CollisionChecker,
    hyperparameters: RrtConnectHyperparameters | None = None,
    *,
    seed: int = 0,
    time_budget_s: float = 10.0,
) -> PlanningResult:
    """Bidirectional RRT: extend one tree toward a sample, connect the other to the new node.

    With the sphere model as the checker (a `CompiledValidity` that answers), the loop runs
    compiled (`compiled_rrt_connect`, the ends and the straight line too): the same search from the
    same samples, without Python between the segment checks. Raises `InvalidMotionQueryError` for
    a malformed or out-of-bounds start/goal, `ValueError` for a seed outside [0, 2^63) (the
    samples' stream, `counter_samples`); a start or goal in collision is reported by the result's
    status.
    """
    seed = checked_seed(seed)
    params = hyperparameters or RrtConnectHyperparameters()
    clock = params.clock
    clock_start = clock()
    deadline = clock_start + time_budget_s
    q_start = space.validated(start, "start")
    q_goal = space.validated(goal, "goal")
    # `CompiledValidity`, asked without isinstance (a runtime protocol check costs 10 us a plan).
    offered = getattr(checker, "compiled_validity", None)
    compiled = offered() if callable(offered) else None
    if compiled is not None:
        from kitchen_tamp.motion.sampling.compiled_rrt_connect import LoopQuery, plan_compiled

        query = LoopQuery(space, seed, params, deadline)
        return plan_compiled(q_start, q_goal, compiled, query).result(clock() - clock_start)
    segments = CountingSegmentChecker(checker, params.edge_resolution)
    start_tree, goal_tree = ConfigurationTree(q_start), ConfigurationTree(q_goal)

    def finish(status: PlanStatus, iterations: int, path: JointPath | None = None) -> PlanningResult:
        return PlanningResult(
            status=status,
            path=path,
            iterations=iterations,
            nodes=len(start_tree) + len(goal_tree),
            collision_checks=segments.configurations_checked,
            planning_time_s=clock() - clock_start,
        )

    endpoint_status = endpoint_collision_status(segments, q_start, q_goal)
    if endpoint_status is not None:
        return finish(endpoint_status, 0)
    if segments.segment_valid(q_start, q_goal, check_start=False, check_end=False):
        return finish(PlanStatus.SOLVED, 0, np.stack([q_start, q_goal]))

    samples = CounterSamples(space.lower, space.upper, seed)
    growing, other = start_tree, goal_tree
    for iteration in range(1, params.max_iterations + 1):
        if clock() >= deadline:
            return finish(PlanStatus.TIME_LIMIT, iteration - 1)
        target = samples.next()
        new = extend_tree(growing, target, segments, params.step_size)
        if new is not None:
            end, reached = connect_tree(other, growing.node(new), segments, params.step_size)
            if reached:
                if growing is start_tree:
                    path = _joined_path(start_tree, new, goal_tree, end)
                else:
                    path = _joined_path(start_tree, end, goal_tree, new)
                return finish(PlanStatus.SOLVED, iteration, path)
        growing, other = other, growing
        if params.tree_balance and len(growing) > params.tree_balance * len(other):
            growing, other = other, growing
    return finish(PlanStatus.ITERATION_LIMIT, params.max_iterations)
