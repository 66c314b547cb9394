"""The shortcut's steps compiled (numba), for the sphere model: `shortcut` without Python between
its segment checks.

Each function is the step of `kitchen_tamp.motion.sampling.shortcut` of the same name, computing
what it computes in the same order of floating-point operations (lengths summed joint by joint, as
`joint_spacing.joint_distance` sums), so that both give the same paths and counts
(`tests/motion/test_compiled_shortcut.py`); every segment is checked by the sphere model's
compiled segment kernel (`segment_checked_in`) in one `validity_scratch` per call. ``counters``
holds the configurations checked (``COUNTER_CHECKS``), and for the random tries the tries made,
the shortcuts taken and the tries in a row that took none.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.segments import segment_checked_in
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import (
    ValidityArrays,
    ValidityScratch,
    validity_scratch,
)
from kitchen_tamp.motion.sampling.rrt_connect_kernel import interval_count, joint_distance

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

COUNTER_CHECKS = 0
COUNTER_TRIES = 1
COUNTER_SHORTCUTS = 2
COUNTER_UNSUCCESSFUL = 3
"""Tries in a row that took no shortcut."""
COUNTER_COUNT = 4


@numba.njit(cache=True)
def _free(
    q0: FloatArray,
    q1: FloatArray,
    resolution: float,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
    counters: IntArray,
) -> bool:
    """`CountingSegmentChecker.segment_valid` of q0 -> q1 with both ends vouched for."""
    free, checked = segment_checked_in(
        q0, q1, interval_count(q0, q1, resolution), False, False, arrays, margin, scratch
    )
    counters[COUNTER_CHECKS] += checked
    return free


@numba.njit(cache=True)
def without_repeats(path: FloatArray) -> FloatArray:
    """The waypoints that differ from the one before them in ``path``."""
    keep = np.ones(path.shape[0], dtype=np.bool_)
    for row in range(1, path.shape[0]):
        keep[row] = np.any(path[row] != path[row - 1])
    return path[keep]


@numba.njit(cache=True)
def path_length(path: FloatArray) -> float:
    """The sum of the segments' `joint_distance`s."""
    length = 0.0
    for row in range(path.shape[0] - 1):
        length += joint_distance(path[row], path[row + 1])
    return length


@numba.njit(cache=True)
def _grid_configuration(q0: FloatArray, q1: FloatArray, index: int, intervals: int) -> FloatArray:
    if index == 0:
        return q0.copy()
    if index == intervals:
        return q1.copy()
    return q0 + (index / intervals) * (q1 - q0)


@numba.njit(cache=True)
def _piece_known_free(
    q0: FloatArray,
    q1: FloatArray,
    grid_steps: int,
    resolution: float,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
    counters: IntArray,
) -> bool:
    if grid_steps == 0 or interval_count(q0, q1, resolution) == grid_steps:
        return True
    return _free(q0, q1, resolution, arrays, margin, scratch, counters)


@numba.njit(cache=True)
def furthest_vertex_jumps(
    path: FloatArray, resolution: float, arrays: ValidityArrays, margin: float, counters: IntArray
) -> IntArray:
    """Indices of the waypoints `connect_furthest_vertices` keeps."""
    scratch = validity_scratch(arrays, path.shape[1])
    kept = [0]
    while kept[-1] < path.shape[0] - 1:
        here = kept[-1]
        reachable = here + 1
        for there in range(path.shape[0] - 1, here + 1, -1):
            if _free(path[here], path[there], resolution, arrays, margin, scratch, counters):
                reachable = there
                break
        kept.append(reachable)
    return np.array(kept)


@numba.njit(cache=True)
def _arcs(path: FloatArray, resolution: float) -> tuple[FloatArray, FloatArray, IntArray]:
    """`shortcut._Arcs.of`: the segments' lengths, their running sums from 0, their intervals."""
    segments = path.shape[0] - 1
    lengths, cumulative = np.empty(segments), np.zeros(segments + 1)
    intervals = np.empty(segments, dtype=np.int64)
    for row in range(segments):
        lengths[row] = joint_distance(path[row], path[row + 1])
        intervals[row] = interval_count(path[row], path[row + 1], resolution)
        cumulative[row + 1] = cumulative[row] + lengths[row]
    return lengths, cumulative, intervals


@numba.njit(cache=True)
def _grid_point(
    arc_length: float, lengths: FloatArray, cumulative: FloatArray, intervals: IntArray
) -> tuple[int, int]:
    """`shortcut._Arcs.grid_point`."""
    segment = min(np.searchsorted(cumulative, arc_length, side="right") - 1, lengths.shape[0] - 1)
    fraction = (arc_length - cumulative[segment]) / max(lengths[segment], 1e-300)
    return segment, min(max(round(fraction * intervals[segment]), 0), intervals[segment])


@numba.njit(cache=True)
def _try_shortcut(
    path: FloatArray,
    units: FloatArray,
    min_improvement: float,
    min_gain_per_length: float,
    resolution: float,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
    counters: IntArray,
) -> tuple[FloatArray, bool]:
    """`shortcut._try_shortcut`: (the shorter path, True), or (``path``, False) when the try takes
    none."""
    lengths, cumulative, intervals = _arcs(path, resolution)
    low_arc, high_arc = units[0] * cumulative[-1], units[1] * cumulative[-1]
    if high_arc < low_arc:
        low_arc, high_arc = high_arc, low_arc
    first, low_index = _grid_point(low_arc, lengths, cumulative, intervals)
    last, high_index = _grid_point(high_arc, lengths, cumulative, intervals)
    if first >= last:
        return path, False
    low_intervals, high_intervals = intervals[first], intervals[last]
    between = 0.0
    for segment in range(first + 1, last):
        between += lengths[segment]
    replaced = (
        lengths[first] * (1.0 - low_index / low_intervals)
        + between
        + lengths[last] * (high_index / high_intervals)
    )
    q_low = _grid_configuration(path[first], path[first + 1], low_index, low_intervals)
    q_high = _grid_configuration(path[last], path[last + 1], high_index, high_intervals)
    direct = joint_distance(q_low, q_high)
    gain = replaced - direct
    if gain <= min_improvement or gain < min_gain_per_length * direct:
        return path, False
    if not (
        _free(q_low, q_high, resolution, arrays, margin, scratch, counters)
        and _piece_known_free(path[first], q_low, low_index, resolution, arrays, margin, scratch, counters)
        and _piece_known_free(
            q_high, path[last + 1], high_intervals - high_index, resolution, arrays, margin, scratch, counters
        )
    ):
        return path, False
    shorter = np.empty((first + 3 + path.shape[0] - last - 1, path.shape[1]))
    shorter[: first + 1] = path[: first + 1]
    shorter[first + 1], shorter[first + 2] = q_low, q_high
    shorter[first + 3 :] = path[last + 1 :]
    return shorter, True


@numba.njit(cache=True)
def random_tries(
    path: FloatArray,
    units: FloatArray,
    max_tries: int,
    patience: int,
    min_improvement: float,
    min_gain_per_length: float,
    resolution: float,
    arrays: ValidityArrays,
    margin: float,
    counters: IntArray,
) -> FloatArray:
    """Random shortcut tries on ``path``, one per row of ``units`` (a try's two uniforms), until
    the rows run out, ``max_tries`` tries in all, ``patience`` tries in a row took none (0: no
    such limit) or the path is one segment; the path they leave."""
    scratch = validity_scratch(arrays, path.shape[1])
    current = path
    for row in range(units.shape[0]):
        if counters[COUNTER_TRIES] >= max_tries or current.shape[0] <= 2:
            break
        if patience > 0 and counters[COUNTER_UNSUCCESSFUL] >= patience:
            break
        shorter, taken = _try_shortcut(
            current,
            units[row],
            min_improvement,
            min_gain_per_length,
            resolution,
            arrays,
            margin,
            scratch,
            counters,
        )
        counters[COUNTER_TRIES] += 1
        if not taken:
            counters[COUNTER_UNSUCCESSFUL] += 1
        else:
            current = without_repeats(shorter)
            counters[COUNTER_SHORTCUTS] += 1
            counters[COUNTER_UNSUCCESSFUL] = 0
    return current


@numba.njit(cache=True)
def pruned(
    path: FloatArray, resolution: float, arrays: ValidityArrays, margin: float, counters: IntArray
) -> FloatArray:
    """`shortcut.prune_waypoints`."""
    scratch = validity_scratch(arrays, path.shape[1])
    keep = np.ones(path.shape[0], dtype=np.bool_)
    last_kept = 0
    for index in range(1, path.shape[0] - 1):
        if _free(path[last_kept], path[index + 1], resolution, arrays, margin, scratch, counters):
            keep[index] = False
        else:
            last_kept = index
    return path[keep]


@numba.njit(cache=True)
def corners_cut(
    path: FloatArray,
    fractions: FloatArray,
    resolution: float,
    arrays: ValidityArrays,
    margin: float,
    counters: IntArray,
) -> FloatArray:
    """`shortcut.cut_corners`, trying each of ``fractions`` in turn."""
    scratch = validity_scratch(arrays, path.shape[1])
    kept = np.empty((2 * path.shape[0], path.shape[1]))
    kept[0] = path[0]
    count = 1
    for index in range(1, path.shape[0] - 1):
        before, corner, after = kept[count - 1].copy(), path[index], path[index + 1]
        incoming = interval_count(before, corner, resolution)
        outgoing = interval_count(corner, after, resolution)
        cut = False
        for fraction in fractions:
            back, forward = round(fraction * incoming), round(fraction * outgoing)
            if back == 0 or forward == 0:
                continue
            cut_start = _grid_configuration(before, corner, incoming - back, incoming)
            cut_end = _grid_configuration(corner, after, forward, outgoing)
            if (
                _free(cut_start, cut_end, resolution, arrays, margin, scratch, counters)
                and _piece_known_free(
                    before, cut_start, incoming - back, resolution, arrays, margin, scratch, counters
                )
                and _piece_known_free(
                    cut_end, after, outgoing - forward, resolution, arrays, margin, scratch, counters
                )
            ):
                kept[count], kept[count + 1] = cut_start, cut_end
                count += 2
                cut = True
                break
        if not cut:
            kept[count] = corner
            count += 1
    kept[count] = path[-1]
    return kept[: count + 1].copy()
