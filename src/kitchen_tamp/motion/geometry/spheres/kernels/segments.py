"""Straight joint-space segments checked by the sphere model in one compiled call each.

`segment_checked` and `free_prefix_checked` visit exactly the configurations
`kitchen_tamp.motion.segment_checking.CountingSegmentChecker` visits, in its order (endpoints,
then the interior coarse to fine; or at multiples of the resolution from ``q0``, block by block,
each block's last first, then its others coarse to fine: `segment_checking.raked_order`), and
return its verdict and the count it would report (the rows of its batches, which start at
``FIRST_BATCH_SIZE`` and double, up to the batch holding the first collision). They differ only
in cost: one call instead of a Python loop of batches, and the validity kernel stops at the first
invalid row (and a batch is interpolated only when the ones before it were free). Configurations
are interpolated without fastmath, so they are numpy's to the bit.

A caller checking many segments in compiled code (the compiled RRT-Connect loop) keeps one
`validity_scratch` and calls `segment_checked_in` and `free_prefix_checked_in`, which work in it
instead of allocating the validity kernel's buffers per segment.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.lanes.buffers import lane_buffers
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.kinematics import LANES
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.screen import first_invalid_in_lanes
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import (
    ValidityArrays,
    ValidityScratch,
    validity_scratch,
)
from kitchen_tamp.motion.segment_checking import FIRST_BATCH_SIZE

FloatArray = npt.NDArray[np.float64]


@numba.njit(cache=True)
def coarse_to_fine_positions(intervals: int) -> npt.NDArray[np.int64]:
    """The interior positions 1 .. intervals - 1 ordered by their lowest set bit, highest first,
    ascending within one bit (the odd multiples of each power of two, the largest power first):
    `kitchen_tamp.joint_spacing.coarse_to_fine_order`, plus one."""
    count = intervals - 1
    positions = np.empty(max(count, 0), dtype=np.int64)
    bit = 1
    while 2 * bit <= count:
        bit *= 2
    row = 0
    while bit >= 1:
        for position in range(bit, count + 1, 2 * bit):
            positions[row] = position
            row += 1
        bit //= 2
    return positions


@numba.njit(cache=True)
def coarse_to_fine_fractions(intervals: int) -> FloatArray:
    """`kitchen_tamp.joint_spacing.interior_fractions` for ``intervals`` intervals."""
    return coarse_to_fine_positions(intervals) / intervals


@numba.njit(cache=True)
def raked_order(count: int, block: int) -> npt.NDArray[np.int64]:
    """`kitchen_tamp.motion.segment_checking.raked_order`: block by block, each block's last
    configuration first, then its others coarse to fine."""
    order = np.empty(count, dtype=np.int64)
    row = 0
    for start in range(0, count, block):
        stop = min(count, start + block)
        order[row] = stop - 1
        row += 1
        for position in coarse_to_fine_positions(stop - start):
            order[row] = start + position - 1
            row += 1
    return order


@numba.njit(cache=True)
def _first_invalid(qs: FloatArray, arrays: ValidityArrays, margin: float, scratch: ValidityScratch) -> int:
    if qs.shape[0] == 0:
        return -1
    valid = valid_rows(qs, arrays, margin, True, scratch)
    for m in range(qs.shape[0]):
        if not valid[m]:
            return m
    return -1


@numba.njit(cache=True)
def _first_invalid_in_batches(
    q0: FloatArray,
    q1: FloatArray,
    shares: FloatArray,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[int, int]:
    """(the first invalid of the configurations ``q0 + share (q1 - q0)`` in ``shares``' order, or
    -1; rows counted as `CountingSegmentChecker` counts them): a batch's configurations are
    interpolated only when the batches before it were free (a failed step is often decided by its
    first configuration)."""
    count, dimension = shares.shape[0], q0.shape[0]
    qs = np.empty((count, dimension))
    lanes = lane_buffers(arrays, dimension)
    start, size = 0, FIRST_BATCH_SIZE
    while start < count:
        stop = min(count, start + size)
        for i in range(start, stop):
            for j in range(dimension):
                qs[i, j] = q0[j] + shares[i] * (q1[j] - q0[j])
        if stop - start >= LANES:
            first = first_invalid_in_lanes(qs[start:stop], arrays, margin, scratch, lanes)
        else:
            first = _first_invalid(qs[start:stop], arrays, margin, scratch)
        if first >= 0:
            return start + first, stop
        start, size = stop, size * 2
    return -1, count


@numba.njit(cache=True)
def segment_checked_in(
    q0: FloatArray,
    q1: FloatArray,
    intervals: int,
    check_start: bool,
    check_end: bool,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[bool, int]:
    """`segment_checked`, working in ``scratch`` (`validity_scratch` of ``arrays``)."""
    ends = int(check_start) + int(check_end)
    if ends:
        end_rows = np.empty((ends, q0.shape[0]))
        row = 0
        if check_start:
            end_rows[row] = q0
            row += 1
        if check_end:
            end_rows[row] = q1
        if _first_invalid(end_rows, arrays, margin, scratch) >= 0:
            return False, ends
    first, checked = _first_invalid_in_batches(
        q0, q1, coarse_to_fine_fractions(intervals), arrays, margin, scratch
    )
    return first < 0, ends + checked


@numba.njit(cache=True)
def segment_checked(
    q0: FloatArray,
    q1: FloatArray,
    intervals: int,
    check_start: bool,
    check_end: bool,
    arrays: ValidityArrays,
    margin: float,
) -> tuple[bool, int]:
    """(whether q0 -> q1 is valid at ``intervals`` intervals, configurations counted): the
    endpoints asked for first, then the interior coarse to fine."""
    scratch = validity_scratch(arrays, q0.shape[0])
    return segment_checked_in(q0, q1, intervals, check_start, check_end, arrays, margin, scratch)


@numba.njit(cache=True)
def free_prefix_checked_in(
    q0: FloatArray,
    q1: FloatArray,
    distance: float,
    resolution: float,
    block: int,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[float, int]:
    """`free_prefix_checked`, working in ``scratch`` (`validity_scratch` of ``arrays``)."""
    steps = int(np.ceil(distance / resolution))
    count = max(steps - 1, 0) + 1
    lengths = np.empty(count)
    for k in range(count - 1):
        lengths[k] = float(k + 1) * resolution
    lengths[count - 1] = (distance / resolution) * resolution
    order = raked_order(count, block)
    shares = np.empty(count)
    for i in range(count):
        shares[i] = lengths[order[i]] / distance
    first, checked = _first_invalid_in_batches(q0, q1, shares, arrays, margin, scratch)
    if first < 0:
        return distance, checked
    free_blocks = order[first] // block
    return (lengths[free_blocks * block - 1] if free_blocks > 0 else 0.0), checked


@numba.njit(cache=True)
def free_prefix_checked(
    q0: FloatArray,
    q1: FloatArray,
    distance: float,
    resolution: float,
    block: int,
    arrays: ValidityArrays,
    margin: float,
) -> tuple[float, int]:
    """(how far from q0 toward q1 is free in whole blocks of ``block`` configurations before the
    first collision, configurations counted): configurations at every multiple of ``resolution``
    from q0, then q1 (``distance`` away), visited in `raked_order`."""
    scratch = validity_scratch(arrays, q0.shape[0])
    return free_prefix_checked_in(q0, q1, distance, resolution, block, arrays, margin, scratch)
