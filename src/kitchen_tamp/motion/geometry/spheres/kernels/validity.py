"""The compiled validity kernel of the sphere model: per configuration, forward kinematics, then
each checked pair at two levels, stopping at the first pair closer than the margin.

The coarse level (a few spheres per link behind one bound per group) clears most pairs; a pair
it cannot clear is opened at the fine level, the tight covering of `sphere_tight_covering` held
in a binary tree of bounding spheres per group (laid out by `sphere_kernel_layout`, searched
by `sphere_tree_walks`).

Compiled by numba on first use and cached on disk (``cache=True``: beside this
file, or where ``NUMBA_CACHE_DIR`` points), so a cold start loads it instead
of compiling again. Arrays only. The helpers are inlined by LLVM (``forceinline``),
not by numba (``inline="always"``), and take arrays with row indices, never rows:
numba counts references to every array a numba-inlined call or a row view touches,
atomically, and in these loops that cost more than the geometry.

Layout (`sphere_kernel_layout`, folded): links in parent-before-child order with
``parents`` (-1 for the root), ``origins`` (L, 4, 4) joint origins, ``kinds``
(`sphere_primitives`: FIXED, REVOLUTE, REVOLUTE_Z, PRISMATIC, or SKIPPED for a fixed
link folded into its moving ancestor, whose spheres ride on that ancestor), ``axes``
(L, 3) unit joint axes and ``variables`` (L) column of the configuration (or -1); a
held joint's motion is folded into its origin. Poses are kept as their top 3x4 rows. The fine
spheres' centres (``fine_centers``) come as x, y and z rows, so a leaf's spheres are placed and
tested in SIMD lanes; so are the coarse ones, transposed per call.

Per configuration, in this order (each step cheap next to the ones it saves): joint limits; the
pair tables' cells (fetched a configuration ahead); kinematics; each group's bound against the
obstacles' distance grid (`distance_grid`: one read clears a group nothing comes near), then
against every box's axis-aligned bounds (one branch-free pass per group), and the few boxes that
come near at the coarse and fine levels; each self pair's bounds, then each group's coarse spheres near the
other's bound (one pass each), then sphere against sphere, then the fine level.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid import grid_clearance
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import (
    box_gap_at,
    folded_link_poses,
    place_point,
    point_box_gap,
    points_apart,
    prefetch,
)
from kitchen_tamp.motion.geometry.spheres.kernels.tree_walks import (
    place_span_once,
    span_near_bound,
    spans_touch,
    tree_hits_box,
    trees_touch,
)
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import (
    ValidityArrays,
    ValidityScratch,
    validity_scratch,
)

FloatArray = npt.NDArray[np.float64]


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _boxes_near(
    x: float,
    y: float,
    z: float,
    reach_squared: float,
    low_x: FloatArray,
    low_y: FloatArray,
    low_z: FloatArray,
    high_x: FloatArray,
    high_y: FloatArray,
    high_z: FloatArray,
) -> int:
    """How many boxes' axis-aligned bounds come within ``reach`` of the point (x, y, z) (branch-free
    over contiguous arrays, so the loop runs in SIMD lanes)."""
    near = 0
    for b in range(low_x.shape[0]):
        ex = max(low_x[b] - x, x - high_x[b], 0.0)
        ey = max(low_y[b] - y, y - high_y[b], 0.0)
        ez = max(low_z[b] - z, z - high_z[b], 0.0)
        near += ex * ex + ey * ey + ez * ez < reach_squared
    return near


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _table_cell(
    qs: FloatArray,
    m: int,
    t: int,
    variables: npt.NDArray[np.int64],
    lows: FloatArray,
    steps: FloatArray,
    counts: npt.NDArray[np.int64],
) -> int:
    """Row-major index in table ``t`` of the cell holding ``qs[m]``'s two joint values (clamped to
    the grid: a value a hair outside the limits belongs to the border cell)."""
    index = 0
    for axis in range(2):
        cell = int(np.floor((qs[m, variables[t, axis]] - lows[t, axis]) / steps[t, axis]))
        cell = min(max(cell, 0), counts[t, axis] - 1)
        index = index * counts[t, axis] + cell
    return index


@numba.njit(cache=True)
def valid_configurations(
    qs: FloatArray,
    arrays: ValidityArrays,
    margin: float,
    stop_at_invalid: bool,
) -> npt.NDArray[np.bool_]:
    """`valid_rows` with buffers of its own (a caller checking many batches keeps one
    `validity_scratch` and calls `valid_rows`)."""
    return valid_rows(qs, arrays, margin, stop_at_invalid, validity_scratch(arrays, qs.shape[1]))


@numba.njit(cache=True, fastmath=True)
def valid_rows(
    qs: FloatArray,
    arrays: ValidityArrays,
    margin: float,
    stop_at_invalid: bool,
    scratch: ValidityScratch,
) -> npt.NDArray[np.bool_]:
    """Per row of ``qs``: within limits and no checked pair of fine spheres closer than ``margin``;
    ``arrays`` holds the model (`sphere_validity_arrays.ValidityArrays`, fields as named below).

    Two levels per pair: the coarse spheres (a few per link, behind one bound per group) clear a
    pair when none comes within the margin; only a pair the coarse level cannot clear is opened
    at the fine level, each group's tight spheres a binary tree of bounding spheres
    (``node_children`` -1 at a leaf, whose spheres are ``node_first:node_last``). Both levels
    cover the same shapes, so the verdict is the fine level's.

    ``group_pairs`` (P, 3) names each pair's table (`sphere_pair_tables`) in its third column, or
    -1. Tables are read first, from the configuration's joints alone: a pair its table proves
    colliding in the configuration's cell (1: clear, -1: colliding, 0: unknown) makes the row
    invalid before any kinematics (when ``margin`` is no smaller than the tables' ``table_margin``),
    and a pair it proves clear is skipped (when ``margin`` is no larger).

    With ``stop_at_invalid`` the rows after the first invalid one are not checked (left True).
    ``scratch`` (`validity_scratch` of the same ``arrays``) is worked in and its stamp advanced."""
    # One argument in, its arrays out once per call (numba counts a reference per field read).
    lower = arrays.lower
    upper = arrays.upper
    root = arrays.root
    parents = arrays.parents
    origins = arrays.origins
    kinds = arrays.kinds
    axes = arrays.axes
    variables = arrays.variables
    group_links = arrays.group_links
    group_centers = arrays.group_centers
    group_radii = arrays.group_radii
    group_starts = arrays.group_starts
    group_stops = arrays.group_stops
    sphere_radii = arrays.sphere_radii
    group_roots = arrays.group_roots
    node_links = arrays.node_links
    node_centers = arrays.node_centers
    node_radii = arrays.node_radii
    node_children = arrays.node_children
    node_first = arrays.node_first
    node_last = arrays.node_last
    fine_centers = arrays.fine_centers
    fine_radii = arrays.fine_radii
    box_rotations = arrays.box_rotations
    box_centers = arrays.box_centers
    box_halves = arrays.box_halves
    box_kinds = arrays.box_kinds
    table_variables = arrays.table_variables
    table_lows = arrays.table_lows
    table_steps = arrays.table_steps
    table_counts = arrays.table_counts
    table_offsets = arrays.table_offsets
    table_cells = arrays.table_cells
    table_margin = arrays.table_margin
    group_pairs = arrays.group_pairs
    coarse_local = arrays.coarse_local
    low_x, low_y, low_z = arrays.low_x, arrays.low_y, arrays.low_z
    high_x, high_y, high_z = arrays.high_x, arrays.high_y, arrays.high_z
    unchecked = arrays.unchecked
    group_order = arrays.group_order
    origin_axes = arrays.origin_axes
    grid_shape, grid_cells = arrays.grid_shape, arrays.grid_cells
    grid_x, grid_y, grid_z = arrays.grid_frame[0], arrays.grid_frame[1], arrays.grid_frame[2]
    grid_scale, grid_outside = 1.0 / arrays.grid_frame[3], arrays.grid_frame[4]
    count = qs.shape[0]
    groups, boxes = group_radii.shape[0], box_halves.shape[0]
    clear_usable, colliding_usable = margin <= table_margin, margin >= table_margin
    (
        pair_state,
        poses,
        frame,
        sines,
        cosines,
        group_world,
        coarse_world,
        coarse_placed,
        fine_world,
        leaf_placed,
        node_world,
        node_placed,
        stack,
        cells,
        last_stamp,
    ) = scratch
    valid = np.ones(count, dtype=np.bool_)
    ordered = group_order.shape[0]
    tolerance = 1e-9
    tables = table_offsets.shape[0]
    first_stamp = last_stamp[0] + 1
    last_stamp[0] += count  # every stamp this call may use, taken now (a stamp marks one row)
    for m in range(count):
        if stop_at_invalid and m > 0 and not valid[m - 1]:
            break  # the rows after the first invalid one are left unchecked (True)
        stamp = first_stamp + m
        # Table cells are far apart in memory, so each lookup would wait on memory: the next row's
        # cells are computed and fetched ahead while this row is checked.
        for ahead in range(m + 1 if m > 0 else 0, min(m + 2, count)):
            for t in range(tables):
                if table_counts[t, 0] * table_counts[t, 1] == 1:  # one cell: nothing to look up
                    cells[ahead & 1, t] = table_offsets[t]
                    continue
                cell = table_offsets[t] + _table_cell(
                    qs, ahead, t, table_variables, table_lows, table_steps, table_counts
                )
                cells[ahead & 1, t] = cell
                prefetch(table_cells, cell)
        for j in range(qs.shape[1]):
            if qs[m, j] < lower[j] - tolerance or qs[m, j] > upper[j] + tolerance:
                valid[m] = False
        if not valid[m]:
            continue
        for k in range(group_pairs.shape[0]):
            t = group_pairs[k, 2]
            pair_state[k] = 0
            if t >= 0:
                state = table_cells[cells[m & 1, t]]
                if (state > 0 and clear_usable) or (state < 0 and colliding_usable):
                    pair_state[k] = state
                if pair_state[k] < 0:
                    valid[m] = False
                    break
        if not valid[m]:
            continue
        folded_link_poses(
            qs, m, root, parents, origins, kinds, axes, variables, origin_axes, poses, frame, sines, cosines
        )
        for g in range(groups):
            place_point(poses, group_links[g], group_centers, g, group_world)
        for o in range(ordered):
            g = group_order[o]
            reach = group_radii[g] + margin
            if reach <= 0.0:
                continue
            x, y, z = group_world[g, 0], group_world[g, 1], group_world[g, 2]
            clearance = grid_clearance(
                x - grid_x, y - grid_y, z - grid_z, grid_scale, grid_outside, grid_shape, grid_cells
            )
            if clearance >= reach:
                continue  # no obstacle within the bound's reach (`distance_grid`)
            if _boxes_near(x, y, z, reach * reach, low_x, low_y, low_z, high_x, high_y, high_z) == 0:
                continue
            for b in range(boxes):
                if unchecked[g * boxes + b] > 0.0:
                    continue
                ex = max(low_x[b] - x, x - high_x[b], 0.0)
                ey = max(low_y[b] - y, y - high_y[b], 0.0)
                ez = max(low_z[b] - z, z - high_z[b], 0.0)
                if ex * ex + ey * ey + ez * ez >= reach * reach:
                    continue
                gap = point_box_gap(group_world, g, box_rotations, box_centers, box_halves, box_kinds, b)
                if gap - group_radii[g] >= margin:
                    continue
                place_span_once(
                    g,
                    coarse_placed,
                    stamp,
                    poses,
                    group_links[g],
                    coarse_local,
                    coarse_world,
                    group_starts[g],
                    group_stops[g],
                )
                coarse_hit = False
                for s in range(group_starts[g], group_stops[g]):
                    gap = box_gap_at(
                        coarse_world[0, s],
                        coarse_world[1, s],
                        coarse_world[2, s],
                        box_rotations,
                        box_centers,
                        box_halves,
                        box_kinds,
                        b,
                    )
                    if gap - sphere_radii[s] < margin:
                        coarse_hit = True
                        break
                if coarse_hit and tree_hits_box(
                    group_roots[g],
                    b,
                    poses,
                    margin,
                    node_links,
                    node_centers,
                    node_radii,
                    node_children,
                    node_first,
                    node_last,
                    node_world,
                    node_placed,
                    fine_centers,
                    fine_radii,
                    fine_world,
                    leaf_placed,
                    box_rotations,
                    box_centers,
                    box_halves,
                    box_kinds,
                    stack,
                    stamp,
                ):
                    valid[m] = False
                    break
            if not valid[m]:
                break
        if not valid[m]:
            continue
        for k in range(group_pairs.shape[0]):
            if pair_state[k] > 0:
                continue
            g, h = group_pairs[k, 0], group_pairs[k, 1]
            if points_apart(group_world, g, group_world, h, group_radii[g] + group_radii[h] + margin):
                continue
            # Each group's coarse spheres near the other's bound, in one SIMD pass each, before any
            # sphere is tested against a sphere: bounds overlap far more often than spheres do.
            coarse_hit = True
            for near, far in ((g, h), (h, g)):
                place_span_once(
                    near,
                    coarse_placed,
                    stamp,
                    poses,
                    group_links[near],
                    coarse_local,
                    coarse_world,
                    group_starts[near],
                    group_stops[near],
                )
                first, last = group_starts[near], group_stops[near]
                if (
                    span_near_bound(
                        first, last, margin, sphere_radii, coarse_world, group_world, far, group_radii[far]
                    )
                    == 0
                ):
                    coarse_hit = False
                    break
            coarse_hit = coarse_hit and spans_touch(
                group_starts[g],
                group_stops[g],
                group_starts[h],
                group_stops[h],
                margin,
                sphere_radii,
                coarse_world,
                group_world,
                h,
                group_radii[h],
            )
            if coarse_hit and trees_touch(
                group_roots[g],
                group_roots[h],
                poses,
                margin,
                node_links,
                node_centers,
                node_radii,
                node_children,
                node_first,
                node_last,
                node_world,
                node_placed,
                fine_centers,
                fine_radii,
                fine_world,
                leaf_placed,
                stack,
                stamp,
            ):
                valid[m] = False
                break
    return valid
