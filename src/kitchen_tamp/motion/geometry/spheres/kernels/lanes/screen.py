"""Eight configurations at once: a screen in SIMD lanes that clears configurations the validity
kernel would accept, so that the kernel checks only the rest.

A free configuration's check in `validity.valid_rows` goes through the same steps for nearly every
configuration: the kinematics, each group's bound read from the obstacles' distance grid, each self
pair's table cell and bounds, and now and then a group's coarse spheres near an obstacle or near
another group. Here those steps run for ``LANES`` configurations side by side in one `simd.Doubles8`
each (the kinematics in `kinematics`); a lane is cleared when every pair the kernel checks is
cleared by one of its own tests, each kept ``SLACK`` to spare for the two computations' rounding:

- every joint within its limits (the kernel's tolerance);
- each group of the arm and every obstacle it is checked against: the group's bound far from the
  obstacle by the distance grid, by the obstacle's axis-aligned bounds or by its exact gap, or else
  each of the group's coarse spheres far from the obstacle by its exact gap;
- each self pair: none its table proves colliding, and each proved clear by its table, by its
  groups' bounds, by no coarse sphere of one group near the other's bound, or by no two coarse
  spheres near each other (each proof where the kernel uses it: the tables by their margin).

The kernel opens its fine spheres only for a pair whose coarse spheres come near, and rejects a
configuration only then or by a table or a limit, so a cleared configuration is one it accepts. A
configuration not cleared is checked by the kernel, which decides: the verdicts, and so every plan
and count, are the kernel's (``tests/motion/test_lanes.py``; a screen clearing 1 mm too close fails
them).
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.codes import SHAPE_CYLINDER, SHAPE_SPHERE
from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid_frame import GRID_UNIT
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.buffers import LaneBuffers
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.kinematics import (
    ALL_LANES,
    LANES,
    lane_link_poses,
    lane_point,
    within_limits,
)
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.simd import (
    abs8,
    at_least8,
    floor8,
    gather8,
    less8,
    load8,
    max8,
    min8,
    splat8,
    sqrt8,
    store8,
)
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import ValidityArrays, ValidityScratch

FloatArray = npt.NDArray[np.float64]

SLACK = 1e-9
"""Metres every clearing test keeps to spare, far above either computation's rounding."""

FALLBACK_LANES = 3
"""Lanes a pair must leave in doubt before their coarse spheres are tested here: a test in lanes costs
the same for one lane as for eight, and fewer are cheaper to leave to the kernel, which rejects a
colliding configuration as soon as it finds it."""


@numba.njit(cache=True, forceinline=True)
def _count(lanes: int) -> int:
    """How many lanes the mask holds."""
    count = 0
    while lanes:
        lanes &= lanes - 1
        count += 1
    return count


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _grid_clears(x: Any, y: Any, z: Any, arrays: ValidityArrays, reach: float) -> int:
    """The lanes where the distance grid (`distance_grid.grid_clearance`) puts the point (x, y, z)
    at least ``reach`` from every obstacle."""
    frame, shape = arrays.grid_frame, arrays.grid_shape
    scale, size_x, size_y, size_z = 1.0 / frame[3], float(shape[0]), float(shape[1]), float(shape[2])
    i, j, k = floor8((x - frame[0]) * scale), floor8((y - frame[1]) * scale), floor8((z - frame[2]) * scale)
    inside = at_least8(i, 0.0) & at_least8(j, 0.0) & at_least8(k, 0.0)
    inside &= less8(i, size_x) & less8(j, size_y) & less8(k, size_z)
    i, j = min8(max8(i, 0.0), size_x - 1.0), min8(max8(j, 0.0), size_y - 1.0)
    k = min8(max8(k, 0.0), size_z - 1.0)
    cells = gather8(arrays.grid_cells, (i * size_y + j) * size_z + k)
    cleared: int = inside & at_least8(cells * GRID_UNIT, reach)
    if frame[4] >= reach:
        cleared |= ALL_LANES & ~inside
    return cleared


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _into_obstacle(dx: Any, dy: Any, dz: Any, arrays: ValidityArrays, b: int) -> tuple[Any, Any, Any]:
    """The offsets (dx, dy, dz) from obstacle ``b``'s centre in its own frame, in every lane."""
    rotation = arrays.box_rotations
    return (
        dx * rotation[b, 0, 0] + dy * rotation[b, 1, 0] + dz * rotation[b, 2, 0],
        dx * rotation[b, 0, 1] + dy * rotation[b, 1, 1] + dz * rotation[b, 2, 1],
        dx * rotation[b, 0, 2] + dy * rotation[b, 1, 2] + dz * rotation[b, 2, 2],
    )


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _obstacle_gap(x: Any, y: Any, z: Any, arrays: ValidityArrays, b: int) -> Any:
    """`primitives.box_gap_at` in every lane: the signed distance from the points to obstacle ``b``
    (a box's or a cylinder's as the length of the outside excess plus the largest excess when
    none is outside, the kernel's two cases in one expression). The obstacle's numbers are read
    first, each field where it is used (`buffers`: a field held across the branches below would
    be counted on entry and dropped on exit)."""
    kind = arrays.box_kinds[b]
    hx, hy, hz = arrays.box_halves[b, 0], arrays.box_halves[b, 1], arrays.box_halves[b, 2]
    dx, dy, dz = x - arrays.box_centers[b, 0], y - arrays.box_centers[b, 1], z - arrays.box_centers[b, 2]
    if kind == SHAPE_SPHERE:
        return sqrt8(dx * dx + dy * dy + dz * dz) - hx
    lx, ly, lz = _into_obstacle(dx, dy, dz, arrays, b)
    if kind == SHAPE_CYLINDER:
        radial, axial = sqrt8(lx * lx + ly * ly) - hx, abs8(lz) - hz
        out_radial, out_axial = max8(radial, 0.0), max8(axial, 0.0)
        return sqrt8(out_radial * out_radial + out_axial * out_axial) + min8(max8(radial, axial), 0.0)
    ex, ey, ez = abs8(lx) - hx, abs8(ly) - hy, abs8(lz) - hz
    ox, oy, oz = max8(ex, 0.0), max8(ey, 0.0), max8(ez, 0.0)
    return sqrt8(ox * ox + oy * oy + oz * oz) + min8(max8(max8(ex, ey), ez), 0.0)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _coarse_sphere_at(s: int, row: int, arrays: ValidityArrays, buffers: LaneBuffers) -> tuple[Any, Any, Any]:
    """Coarse sphere ``s``'s centre in the world in every lane (``row``: where its link's pose
    starts in ``buffers.poses``)."""
    x, y, z = arrays.coarse_local[0, s], arrays.coarse_local[1, s], arrays.coarse_local[2, s]
    poses = buffers.poses
    return (
        lane_point(poses, row, x, y, z),
        lane_point(poses, row + 4 * LANES, x, y, z),
        lane_point(poses, row + 8 * LANES, x, y, z),
    )


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _spheres_clear_obstacle(
    g: int, b: int, lanes: int, arrays: ValidityArrays, margin: float, buffers: LaneBuffers
) -> int:
    """Of ``lanes``, those where each of group ``g``'s coarse spheres is at least its radius and the
    margin from obstacle ``b``."""
    row = arrays.group_links[g] * 12 * LANES
    for s in range(arrays.group_starts[g], arrays.group_stops[g]):
        wx, wy, wz = _coarse_sphere_at(s, row, arrays, buffers)
        gap = _obstacle_gap(wx, wy, wz, arrays, b)
        lanes &= at_least8(gap, arrays.sphere_radii[s] + margin + SLACK)
        if lanes == 0:
            break
    return lanes


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _group_clears_obstacles(
    g: int, lanes: int, arrays: ValidityArrays, margin: float, buffers: LaneBuffers
) -> int:
    """Of ``lanes``, those where group ``g`` is cleared of every obstacle it is checked against:
    the obstacle's bounds or exact gap far from the group's bound, or else each coarse sphere far."""
    bound = g * 3 * LANES
    x, y = load8(buffers.group_world, bound), load8(buffers.group_world, bound + LANES)
    z = load8(buffers.group_world, bound + 2 * LANES)
    reach, boxes = arrays.group_radii[g] + margin + SLACK, arrays.box_kinds.shape[0]
    for b in range(boxes):
        if arrays.unchecked[g * boxes + b] > 0.0:
            continue
        ex = max8(max8(arrays.low_x[b] - x, x - arrays.high_x[b]), 0.0)
        ey = max8(max8(arrays.low_y[b] - y, y - arrays.high_y[b]), 0.0)
        ez = max8(max8(arrays.low_z[b] - z, z - arrays.high_z[b]), 0.0)
        near = lanes & less8(ex * ex + ey * ey + ez * ez, reach * reach)
        if near:
            near &= less8(_obstacle_gap(x, y, z, arrays, b), reach)
        if _count(near) >= FALLBACK_LANES:
            lanes &= ~near | _spheres_clear_obstacle(g, b, near, arrays, margin, buffers)
        elif near:
            lanes &= ~near
            if lanes == 0:
                break
    return lanes


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _placed_group_bound(g: int, arrays: ValidityArrays, buffers: LaneBuffers) -> tuple[Any, Any, Any]:
    """Group ``g``'s bound's centre in every lane, also stored in ``buffers.group_world``."""
    row, bound = arrays.group_links[g] * 12 * LANES, g * 3 * LANES
    cx, cy, cz = arrays.group_centers[g, 0], arrays.group_centers[g, 1], arrays.group_centers[g, 2]
    x = lane_point(buffers.poses, row, cx, cy, cz)
    y = lane_point(buffers.poses, row + 4 * LANES, cx, cy, cz)
    z = lane_point(buffers.poses, row + 8 * LANES, cx, cy, cz)
    store8(buffers.group_world, bound, x)
    store8(buffers.group_world, bound + LANES, y)
    store8(buffers.group_world, bound + 2 * LANES, z)
    return x, y, z


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _obstacles_clear(arrays: ValidityArrays, margin: float, buffers: LaneBuffers, cleared: int) -> int:
    """Of the lanes ``cleared``, those where every group is cleared of every obstacle; each group's
    bound placed in ``buffers.group_world`` on the way."""
    for g in range(arrays.group_radii.shape[0]):
        x, y, z = _placed_group_bound(g, arrays, buffers)
        reach = arrays.group_radii[g] + margin
        if cleared == 0:
            break
        if reach <= 0.0:
            continue
        doubtful = cleared & ~_grid_clears(x, y, z, arrays, reach + SLACK)
        if doubtful:
            cleared &= ~doubtful | _group_clears_obstacles(g, doubtful, arrays, margin, buffers)
    return cleared


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _table_states(values: FloatArray, t: int, arrays: ValidityArrays) -> Any:
    """Each lane's cell of pair table ``t`` (as `validity._table_cell` finds it), read."""
    lows, steps, counts = arrays.table_lows, arrays.table_steps, arrays.table_counts
    index = splat8(0.0)
    for axis in range(2):
        value = load8(values, arrays.table_variables[t, axis] * LANES)
        cell = min8(max8(floor8((value - lows[t, axis]) / steps[t, axis]), 0.0), float(counts[t, axis] - 1))
        index = index * float(counts[t, axis]) + cell
    return gather8(arrays.table_cells, index + float(arrays.table_offsets[t]))


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _spheres_near_bound(
    g: int, h: int, lanes: int, arrays: ValidityArrays, margin: float, buffers: LaneBuffers
) -> int:
    """Of ``lanes``, those where some coarse sphere of group ``g`` comes near group ``h``'s bound."""
    row, bound = arrays.group_links[g] * 12 * LANES, h * 3 * LANES
    bx, by = load8(buffers.group_world, bound), load8(buffers.group_world, bound + LANES)
    bz = load8(buffers.group_world, bound + 2 * LANES)
    near = 0
    for s in range(arrays.group_starts[g], arrays.group_stops[g]):
        dx, dy, dz = _coarse_sphere_at(s, row, arrays, buffers)
        dx, dy, dz = dx - bx, dy - by, dz - bz
        reach = arrays.sphere_radii[s] + arrays.group_radii[h] + margin + SLACK
        near |= lanes & less8(dx * dx + dy * dy + dz * dz, reach * reach)
        if near == lanes:
            break
    return near


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _coarse_pair_clear(
    g: int, h: int, lanes: int, arrays: ValidityArrays, margin: float, buffers: LaneBuffers
) -> int:
    """Of ``lanes``, those where the kernel's coarse level clears the self pair (g, h): no coarse
    sphere of one group near the other's bound, or no two of their coarse spheres near."""
    near = _spheres_near_bound(g, h, lanes, arrays, margin, buffers)
    if near:
        near = _spheres_near_bound(h, g, near, arrays, margin, buffers)
    g_row, h_row = arrays.group_links[g] * 12 * LANES, arrays.group_links[h] * 12 * LANES
    apart = near
    for s in range(arrays.group_starts[g], arrays.group_stops[g]):
        if apart == 0:
            break
        sx, sy, sz = _coarse_sphere_at(s, g_row, arrays, buffers)
        for u in range(arrays.group_starts[h], arrays.group_stops[h]):
            ux, uy, uz = _coarse_sphere_at(u, h_row, arrays, buffers)
            dx, dy, dz = sx - ux, sy - uy, sz - uz
            reach = arrays.sphere_radii[s] + arrays.sphere_radii[u] + margin + SLACK
            if reach > 0.0:
                apart &= at_least8(dx * dx + dy * dy + dz * dz, reach * reach)
    return lanes & (~near | apart)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _tables_read(arrays: ValidityArrays, margin: float, buffers: LaneBuffers, cleared: int) -> int:
    """Of the lanes ``cleared``, those no pair table proves colliding; per self pair, the lanes its
    table proves clear into ``buffers.proved`` (each proof where the kernel uses it). Read before
    the kinematics, as the kernel reads them: a configuration a table rejects costs nothing more."""
    clear_usable, colliding_usable = margin <= arrays.table_margin, margin >= arrays.table_margin
    for k in range(arrays.group_pairs.shape[0]):
        buffers.proved[k] = 0
        t = arrays.group_pairs[k, 2]
        if t < 0:
            continue
        states = _table_states(buffers.values, t, arrays)
        if clear_usable:
            buffers.proved[k] = at_least8(states, 0.5)
        if colliding_usable:
            cleared &= ~less8(states, -0.5)
    return cleared


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _bounds_near(k: int, arrays: ValidityArrays, margin: float, buffers: LaneBuffers) -> int:
    """The lanes where self pair ``k``'s two group bounds come within their radii and the margin
    (none when the margin makes the pair empty: the kernel checks no such pair)."""
    g, h = arrays.group_pairs[k, 0], arrays.group_pairs[k, 1]
    reach = arrays.group_radii[g] + arrays.group_radii[h] + margin + SLACK
    if reach <= SLACK:
        return 0
    world = buffers.group_world
    dx = load8(world, g * 3 * LANES) - load8(world, h * 3 * LANES)
    dy = load8(world, (g * 3 + 1) * LANES) - load8(world, (h * 3 + 1) * LANES)
    dz = load8(world, (g * 3 + 2) * LANES) - load8(world, (h * 3 + 2) * LANES)
    near: int = less8(dx * dx + dy * dy + dz * dz, reach * reach)
    return near


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _self_pairs_clear(arrays: ValidityArrays, margin: float, buffers: LaneBuffers, cleared: int) -> int:
    """Of the lanes ``cleared``, those where each self pair is proved clear by its table
    (`_tables_read`), its groups' bounds or their coarse spheres."""
    for k in range(arrays.group_pairs.shape[0]):
        doubtful = cleared & ~buffers.proved[k]
        if doubtful == 0:
            continue
        doubtful &= _bounds_near(k, arrays, margin, buffers)
        if _count(doubtful) >= FALLBACK_LANES:
            g, h = arrays.group_pairs[k, 0], arrays.group_pairs[k, 1]
            cleared &= ~doubtful | _coarse_pair_clear(g, h, doubtful, arrays, margin, buffers)
        elif doubtful:
            cleared &= ~doubtful
            if cleared == 0:
                break
    return cleared


@numba.njit(cache=True, fastmath=True)
def lanes_cleared(
    qs: FloatArray, first: int, arrays: ValidityArrays, margin: float, buffers: LaneBuffers
) -> int:
    """Screen rows ``first`` .. ``first + LANES`` of ``qs`` (past its end, the lanes repeat its last
    row): bit ``k`` set when row ``first + k`` is cleared, a configuration the kernel accepts.
    Each step takes the buffers whole and reads a field where it uses it (`buffers`)."""
    rows = min(LANES, qs.shape[0] - first)
    for lane in range(LANES):
        row = first + min(lane, rows - 1)
        for j in range(qs.shape[1]):
            buffers.values[j * LANES + lane] = qs[row, j]
    cleared = within_limits(buffers.values, arrays.lower, arrays.upper)
    cleared = _tables_read(arrays, margin, buffers, cleared)
    if cleared == 0:
        return 0
    lane_link_poses(arrays, buffers.values, buffers.sines, buffers.cosines, buffers.poses)
    cleared = _obstacles_clear(arrays, margin, buffers, cleared)
    return int(_self_pairs_clear(arrays, margin, buffers, cleared) & ((1 << rows) - 1))


@numba.njit(cache=True)
def first_invalid_in_lanes(
    qs: FloatArray, arrays: ValidityArrays, margin: float, scratch: ValidityScratch, buffers: LaneBuffers
) -> int:
    """The first row of ``qs`` the validity kernel rejects, or -1: ``LANES`` rows at a time screened
    (`lanes_cleared`), the rows not cleared checked by `valid_rows` (working in ``scratch``)."""
    for first in range(0, qs.shape[0], LANES):
        cleared = lanes_cleared(qs, first, arrays, margin, buffers)
        count = 0
        for lane in range(min(LANES, qs.shape[0] - first)):
            if not cleared >> lane & 1:
                for j in range(qs.shape[1]):
                    buffers.left[count, j] = qs[first + lane, j]
                buffers.left_rows[count] = first + lane
                count += 1
        if count == 0:
            continue
        valid = valid_rows(buffers.left[:count], arrays, margin, True, scratch)
        for i in range(count):
            if not valid[i]:
                return int(buffers.left_rows[i])
    return -1
