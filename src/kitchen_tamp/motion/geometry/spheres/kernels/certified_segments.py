"""Segment checks that skip configurations a clearance bound proves free: the same verdicts as
checking every configuration at the resolution, from a fraction of the configurations.

A free 1 rad step checked at 0.01 rad costs 100 configurations, most of them far from anything.
Here a configuration visited on a segment ``q(t) = q0 + t (q1 - q0)`` is bounded: how much further
than the margin every checked obstacle and self pair is (each group's bounding sphere first, then
its medium spheres, then its coarse spheres, each level holding the next: `walk_bounds`), and how
fast the arm can close that gap along the segment:

- a point on a link moves, per unit of ``t``, at most ``sum_j |q1_j - q0_j| r_j``, where ``r_j``
  bounds its distance from joint j's axis (`walk_bounds.group_reaches`); a prismatic joint moves it
  at ``|q1_j - q0_j|``;
- the signed distance to a box, sphere or cylinder changes no faster than the point moves, and the
  distance between two points of the arm no faster than the joints carrying only one of them move
  it (a joint carrying both turns them together, their distance unchanged);
- so a pair clear by ``c`` whose spheres close in at ``v`` per unit ``t`` stays clear for ``c / v``.

Every configuration within that reach is one the validity kernel (`validity.valid_rows`) calls
valid: its coarse level clears every pair there (a pair table could only reject a cell where the
coarse spheres come within the margin everywhere). A pair with a table is read from its table
instead, configuration by configuration (the skip stops at the first whose cell it does not prove
clear). Where no bound clears a configuration (some coarse pair within the margin plus ``SAFETY``)
the validity kernel checks it, with the next few in a batch. So the first invalid configuration
met is the one the dense walk meets, and a segment is valid exactly when the dense check says so.

Segments are visited coarse to fine (a collision anywhere is met early) and a bound clears both
ways; a free prefix is walked from its start. What is counted is configurations visited: bounds
taken and configurations checked.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.primitives import (
    box_gap_at,
    folded_link_poses,
    place_point,
)
from kitchen_tamp.motion.geometry.spheres.kernels.segments import coarse_to_fine_fractions
from kitchen_tamp.motion.geometry.spheres.kernels.tree_walks import place_span_once
from kitchen_tamp.motion.geometry.spheres.kernels.validity import boxes_near, valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import ValidityArrays, ValidityScratch

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

SAFETY = 1e-7
"""Metres of clearance a bound keeps in hand, beyond the margin, for rounding (the validity kernel
and this one compute the same distances in different orders)."""
NOT_CLEARED = -1.0
"""`_cleared_reach`'s answer when some coarse pair is within the margin plus ``SAFETY``."""
REACH_CAP = 16.0
"""Configurations a bound is asked to clear on either side at most (pairs that cannot limit it are
not looked at; most bounds near obstacles reach a few)."""
FIRST_BATCH = 4
"""Configurations checked together where a bound fails (doubling while bounds keep failing)."""
MAX_BATCH = 64
"""The largest such batch."""
FAR = 1e300
"""Stands for infinity in compiled code built with fastmath (which assumes no infinities): a
candidate already opened, and (negated) a pair's clearance not yet known."""
CELL_SLACK = 1e-9
"""Radians either side of a joint value whose table cells must all be clear (the kernel computes a
cell with its own rounding; a value that close to a cell border is read in both cells)."""


@numba.njit(cache=True)
def group_speeds(
    q0: FloatArray, q1: FloatArray, arrays: ValidityArrays, speeds: FloatArray, pair_speeds: FloatArray
) -> None:
    """``speeds[g]``: how far any coarse sphere of group g (or its bound's centre) can move per unit
    of ``t`` along q0 -> q1; ``pair_speeds[k]``: how fast the distance between two points of self
    pair k's groups can change. A joint that carries both groups moves them rigidly together
    (their distance unchanged), so only the joints carrying one of the two count."""
    reaches, variables, group_pairs = arrays.group_reaches, arrays.variables, arrays.group_pairs
    rates = np.zeros(reaches.shape[1])
    for link in range(reaches.shape[1]):
        if variables[link] >= 0:
            rates[link] = abs(q1[variables[link]] - q0[variables[link]])
    for g in range(reaches.shape[0]):
        speed = 0.0
        for link in range(reaches.shape[1]):
            speed += reaches[g, link] * rates[link]
        speeds[g] = speed * (1.0 + 1e-9) + 1e-300
    for k in range(group_pairs.shape[0]):
        g, h = group_pairs[k, 0], group_pairs[k, 1]
        speed = 0.0
        for link in range(reaches.shape[1]):
            if (reaches[g, link] > 0.0) != (reaches[h, link] > 0.0):
                speed += (reaches[g, link] + reaches[h, link]) * rates[link]
        pair_speeds[k] = speed * (1.0 + 1e-9) + 1e-300


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _box_pair_clearance(
    first: int,
    last: int,
    b: int,
    within: float,
    margin: float,
    coarse_world: FloatArray,
    radii: FloatArray,
    rotations: FloatArray,
    centers: FloatArray,
    halves: FloatArray,
    kinds: IntArray,
) -> float:
    """The least clearance of the coarse spheres ``first:last`` (placed) to box b, or ``within``
    when none is below it."""
    least = within
    for s in range(first, last):
        x, y, z = coarse_world[0, s], coarse_world[1, s], coarse_world[2, s]
        gap = box_gap_at(x, y, z, rotations, centers, halves, kinds, b)
        least = min(least, gap - radii[s] - margin - SAFETY)
    return least


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _self_pair_clearance(
    first_g: int,
    last_g: int,
    first_h: int,
    last_h: int,
    h: int,
    bound_radius: float,
    within: float,
    margin: float,
    coarse_world: FloatArray,
    group_world: FloatArray,
    radii: FloatArray,
) -> float:
    """The least clearance between the coarse spheres ``first_g:last_g`` and ``first_h:last_h`` of
    group h (placed), or ``within`` when none is below it: a sphere of the first is opened against
    the second only when it comes that close to h's bound (radius ``bound_radius``)."""
    least = within
    for s in range(first_g, last_g):
        x, y, z = coarse_world[0, s], coarse_world[1, s], coarse_world[2, s]
        dx, dy, dz = group_world[h, 0] - x, group_world[h, 1] - y, group_world[h, 2] - z
        reach = radii[s] + margin + SAFETY
        if math.sqrt(dx * dx + dy * dy + dz * dz) - reach - bound_radius >= least:
            continue
        for u in range(first_h, last_h):
            dx, dy, dz = coarse_world[0, u] - x, coarse_world[1, u] - y, coarse_world[2, u] - z
            squared = dx * dx + dy * dy + dz * dz
            limit = least + reach + radii[u]
            if limit > 0.0 and squared >= limit * limit:
                continue
            least = min(least, math.sqrt(squared) - reach - radii[u])
    return least


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _place_medium(
    g: int,
    stamp: int,
    poses: FloatArray,
    link: int,
    medium_local: FloatArray,
    medium_world: FloatArray,
    medium_placed: IntArray,
    first: int,
    last: int,
) -> None:
    """Group g's medium spheres ``first:last`` in the world, once per configuration (``stamp``)."""
    if medium_placed[g] != stamp:
        for i in range(first, last):
            place_point(poses, link, medium_local, i, medium_world)
        medium_placed[g] = stamp


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _medium_box_clearance(
    first: int,
    last: int,
    b: int,
    within: float,
    margin: float,
    medium_world: FloatArray,
    medium_radii: FloatArray,
    rotations: FloatArray,
    centers: FloatArray,
    halves: FloatArray,
    kinds: IntArray,
) -> float:
    """The least clearance of the medium spheres ``first:last`` (placed) to box b, or ``within``."""
    least = within
    for i in range(first, last):
        x, y, z = medium_world[i, 0], medium_world[i, 1], medium_world[i, 2]
        gap = box_gap_at(x, y, z, rotations, centers, halves, kinds, b)
        least = min(least, gap - medium_radii[i] - margin - SAFETY)
    return least


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _medium_pair_clearance(
    first_g: int,
    last_g: int,
    first_h: int,
    last_h: int,
    within: float,
    margin: float,
    medium_world: FloatArray,
    medium_radii: FloatArray,
) -> float:
    """The least clearance between the medium spheres ``first_g:last_g`` and ``first_h:last_h``
    (placed), or ``within``."""
    least = within
    for i in range(first_g, last_g):
        for j in range(first_h, last_h):
            dx = medium_world[i, 0] - medium_world[j, 0]
            dy = medium_world[i, 1] - medium_world[j, 1]
            dz = medium_world[i, 2] - medium_world[j, 2]
            gap = math.sqrt(dx * dx + dy * dy + dz * dz) - medium_radii[i] - medium_radii[j]
            least = min(least, gap - margin - SAFETY)
    return least


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _cleared_reach(
    wanted: float,
    at: float,
    margin: float,
    speeds: FloatArray,
    pair_speeds: FloatArray,
    slowness: FloatArray,
    pair_slowness: FloatArray,
    tables_read: bool,
    known: FloatArray,
    known_at: FloatArray,
    candidates: FloatArray,
    candidate_pairs: IntArray,
    stamp: int,
    poses: FloatArray,
    group_world: FloatArray,
    coarse_world: FloatArray,
    coarse_placed: IntArray,
    group_links: IntArray,
    group_radii: FloatArray,
    group_starts: IntArray,
    group_stops: IntArray,
    sphere_radii: FloatArray,
    coarse_local: FloatArray,
    box_rotations: FloatArray,
    box_centers: FloatArray,
    box_halves: FloatArray,
    box_kinds: IntArray,
    low_x: FloatArray,
    low_y: FloatArray,
    low_z: FloatArray,
    high_x: FloatArray,
    high_y: FloatArray,
    high_z: FloatArray,
    unchecked: FloatArray,
    group_order: IntArray,
    group_pairs: IntArray,
    medium_local: FloatArray,
    medium_radii: FloatArray,
    medium_starts: IntArray,
    medium_stops: IntArray,
    medium_world: FloatArray,
    medium_placed: IntArray,
) -> float:
    """How far in ``t`` either way from the configuration at ``t = at`` (its link poses in ``poses``,
    its group bounds placed in ``group_world``; at most ``wanted``) the coarse spheres stay clear
    of every checked pair by the margin (pairs with a table left out when ``tables_read``), or
    ``NOT_CLEARED``.

    Branch and bound: each pair is first bounded cheaply, by its groups' bounding spheres (a box by
    its axis-aligned bounds) or by the clearance it had where it was last opened on this segment
    (``known`` at ``known_at``, less what its speed can take since); then, nearest first, the pairs
    whose bound limits the answer are opened, to their medium spheres (`walk_bounds`), and to their
    coarse spheres only where the medium ones come within the margin (each result remembered),
    until no unopened bound limits it. ``candidates`` and ``candidate_pairs`` are scratch with a
    row for every pair (0 for a box pair or 1 + k for self pair k, then its two indices)."""
    boxes = box_halves.shape[0]
    self_slots = group_radii.shape[0] * boxes
    found = 0
    best = wanted
    for o in range(group_order.shape[0]):
        g = group_order[o]
        reach = group_radii[g] + margin + SAFETY
        x, y, z = group_world[g, 0], group_world[g, 1], group_world[g, 2]
        needed = reach + wanted * speeds[g]
        if boxes_near(x, y, z, needed * needed, low_x, low_y, low_z, high_x, high_y, high_z) == 0:
            continue  # one branch-free pass: most groups are far from every box
        for b in range(boxes):
            # The box's axis-aligned bounds hold it: their distance is a lower bound of its own.
            ex = max(low_x[b] - x, x - high_x[b], 0.0)
            ey = max(low_y[b] - y, y - high_y[b], 0.0)
            ez = max(low_z[b] - z, z - high_z[b], 0.0)
            squared = ex * ex + ey * ey + ez * ez + unchecked[g * boxes + b]
            if squared >= needed * needed:
                continue
            slot = g * boxes + b
            clearance = max(math.sqrt(squared) - reach, known[slot] - speeds[g] * abs(at - known_at[slot]))
            candidates[found] = clearance * slowness[g]
            candidate_pairs[found, 0], candidate_pairs[found, 1], candidate_pairs[found, 2] = 0, g, b
            found += 1
    for k in range(group_pairs.shape[0]):
        if tables_read and group_pairs[k, 2] >= 0:
            continue
        g, h = group_pairs[k, 0], group_pairs[k, 1]
        speed = pair_speeds[k]
        dx = group_world[g, 0] - group_world[h, 0]
        dy = group_world[g, 1] - group_world[h, 1]
        dz = group_world[g, 2] - group_world[h, 2]
        clearance = math.sqrt(dx * dx + dy * dy + dz * dz) - group_radii[g] - group_radii[h] - margin - SAFETY
        slot = self_slots + k
        clearance = max(clearance, known[slot] - speed * abs(at - known_at[slot]))
        if clearance >= wanted * speed:
            continue
        candidates[found] = clearance * pair_slowness[k]
        candidate_pairs[found, 0], candidate_pairs[found, 1], candidate_pairs[found, 2] = 1 + k, g, h
        found += 1
    while True:
        nearest, nearest_value = -1, best
        for i in range(found):
            if candidates[i] < nearest_value:
                nearest, nearest_value = i, candidates[i]
        if nearest < 0:
            return best
        candidates[nearest] = FAR
        kind, g, other = candidate_pairs[nearest, 0], candidate_pairs[nearest, 1], candidate_pairs[nearest, 2]
        link, first_m, last_m = group_links[g], medium_starts[g], medium_stops[g]
        _place_medium(g, stamp, poses, link, medium_local, medium_world, medium_placed, first_m, last_m)
        if kind == 0:
            speed, per_speed, slot = speeds[g], slowness[g], g * boxes + other
            clearance = _medium_box_clearance(
                first_m, last_m, other, best * speed, margin, medium_world, medium_radii,
                box_rotations, box_centers, box_halves, box_kinds,
            )  # fmt: skip
        else:
            speed, per_speed, slot = pair_speeds[kind - 1], pair_slowness[kind - 1], self_slots + kind - 1
            first_n, last_n = medium_starts[other], medium_stops[other]
            _place_medium(
                other,
                stamp,
                poses,
                group_links[other],
                medium_local,
                medium_world,
                medium_placed,
                first_n,
                last_n,
            )
            clearance = _medium_pair_clearance(
                first_m, last_m, first_n, last_n, best * speed, margin, medium_world, medium_radii
            )
        if clearance < 0.0:  # the medium spheres come within the margin: the coarse ones decide
            first, last = group_starts[g], group_stops[g]
            place_span_once(g, coarse_placed, stamp, poses, link, coarse_local, coarse_world, first, last)
            if kind == 0:
                clearance = _box_pair_clearance(
                    first, last, other, best * speed, margin, coarse_world, sphere_radii,
                    box_rotations, box_centers, box_halves, box_kinds,
                )  # fmt: skip
            else:
                first_h, last_h = group_starts[other], group_stops[other]
                place_span_once(
                    other,
                    coarse_placed,
                    stamp,
                    poses,
                    group_links[other],
                    coarse_local,
                    coarse_world,
                    first_h,
                    last_h,
                )
                clearance = _self_pair_clearance(
                    first, last, first_h, last_h, other, group_radii[other], best * speed, margin,
                    coarse_world, group_world, sphere_radii,
                )  # fmt: skip
            if clearance < 0.0:
                return NOT_CLEARED
        known[slot], known_at[slot] = clearance, at
        best = min(best, clearance * per_speed)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _cells_near(value: float, low: float, inverse_step: float, count: int) -> tuple[int, int]:
    """The first and last grid cell (clamped) within ``CELL_SLACK`` of the joint value."""
    first = min(max(int(np.floor((value - CELL_SLACK - low) * inverse_step)), 0), count - 1)
    last = min(max(int(np.floor((value + CELL_SLACK - low) * inverse_step)), 0), count - 1)
    return first, last


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _cells_clear(
    q0: FloatArray,
    q1: FloatArray,
    at: float,
    group_pairs: IntArray,
    cells: npt.NDArray[np.int8],
    offsets: IntArray,
    variables: IntArray,
    lows: FloatArray,
    inverse_steps: FloatArray,
    counts: IntArray,
) -> bool:
    """Whether every pair with a table has its cell proved clear at ``q0 + at (q1 - q0)`` (and
    within ``CELL_SLACK`` of it, which covers rounding: the kernel computes cells its own way)."""
    for k in range(group_pairs.shape[0]):
        t = group_pairs[k, 2]
        if t < 0:
            continue
        c0, c1 = variables[t, 0], variables[t, 1]
        value_0, value_1 = q0[c0] + at * (q1[c0] - q0[c0]), q0[c1] + at * (q1[c1] - q0[c1])
        first_0, last_0 = _cells_near(value_0, lows[t, 0], inverse_steps[t, 0], counts[t, 0])
        first_1, last_1 = _cells_near(value_1, lows[t, 1], inverse_steps[t, 1], counts[t, 1])
        for i in range(first_0, last_0 + 1):
            for j in range(first_1, last_1 + 1):
                if cells[offsets[t] + i * counts[t, 1] + j] <= 0:
                    return False
    return True


@numba.njit(cache=True)
def _place_row(q0: FloatArray, q1: FloatArray, at: float, row: FloatArray) -> None:
    """row[0] = q0 + at (q1 - q0), as the dense checks compute it (without fastmath: the same bits)."""
    for j in range(q0.shape[0]):
        row[0, j] = q0[j] + at * (q1[j] - q0[j])


@numba.njit(cache=True)
def _within_limits(q: FloatArray, lower: FloatArray, upper: FloatArray) -> bool:
    for j in range(q.shape[0]):  # noqa: SIM110
        if q[j] < lower[j] - 1e-9 or q[j] > upper[j] + 1e-9:
            return False
    return True


@numba.njit(cache=True, fastmath=True)
def certified_walk(
    q0: FloatArray,
    q1: FloatArray,
    fractions: FloatArray,
    order: IntArray,
    both_ways: bool,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[int, int]:
    """(the index into ``fractions`` of the first invalid configuration ``q0 + f (q1 - q0)`` met,
    visiting ``fractions`` in ``order`` (ascending fractions within [0, 1]), or -1; configurations
    visited). A visited configuration whose coarse spheres clear every pair is proved free with
    the configurations within its bound's reach, ahead (and behind, ``both_ways``), which are not
    visited; the others are checked by `valid_rows`. With an end outside the joint limits, every
    configuration is checked."""
    # The arrays out of their structure once per segment (numba counts a reference per field read).
    group_links, group_centers, group_radii = arrays.group_links, arrays.group_centers, arrays.group_radii
    box_rotations, box_centers = arrays.box_rotations, arrays.box_centers
    box_halves, box_kinds = arrays.box_halves, arrays.box_kinds
    low_x, low_y, low_z = arrays.low_x, arrays.low_y, arrays.low_z
    high_x, high_y, high_z = arrays.high_x, arrays.high_y, arrays.high_z
    unchecked, group_order, group_pairs = arrays.unchecked, arrays.group_order, arrays.group_pairs
    group_starts, group_stops, sphere_radii = arrays.group_starts, arrays.group_stops, arrays.sphere_radii
    coarse_local = arrays.coarse_local
    root, parents, origins, kinds, axes = (
        arrays.root,
        arrays.parents,
        arrays.origins,
        arrays.kinds,
        arrays.axes,
    )
    variables = arrays.variables
    table_cells, table_offsets, table_variables = (
        arrays.table_cells,
        arrays.table_offsets,
        arrays.table_variables,
    )
    table_lows, table_steps, table_counts = arrays.table_lows, arrays.table_steps, arrays.table_counts
    medium_local, medium_radii = arrays.medium_centers, arrays.medium_radii
    medium_starts, medium_stops = arrays.medium_starts, arrays.medium_stops
    medium_world, medium_placed = (
        np.empty((medium_radii.shape[0], 3)),
        np.zeros(group_radii.shape[0], dtype=np.int64),
    )
    poses, frame, sines, cosines = scratch[1], scratch[2], scratch[3], scratch[4]
    group_world, coarse_world, coarse_placed, last_stamp = scratch[5], scratch[6], scratch[7], scratch[14]
    bounded = _within_limits(q0, arrays.lower, arrays.upper) and _within_limits(
        q1, arrays.lower, arrays.upper
    )
    tables_read = margin <= arrays.table_margin and table_offsets.shape[0] > 0
    groups = group_radii.shape[0]
    speeds, pair_speeds = np.empty(groups), np.empty(group_pairs.shape[0])
    group_speeds(q0, q1, arrays, speeds, pair_speeds)
    slowness, pair_slowness = 1.0 / speeds, 1.0 / pair_speeds  # multiplied by, not divided by, per pair
    pairs = groups * box_halves.shape[0] + group_pairs.shape[0]
    known, known_at = np.full(pairs, -FAR), np.zeros(pairs)
    candidates, candidate_pairs = np.empty(pairs), np.empty((pairs, 3), dtype=np.int64)
    inverse_steps = 1.0 / table_steps
    rows = np.empty((MAX_BATCH, q0.shape[0]))
    batch_rows = np.empty(MAX_BATCH, dtype=np.int64)
    count = fractions.shape[0]
    free = np.zeros(count, dtype=np.bool_)
    visited, batch, i = 0, FIRST_BATCH, 0
    while i < order.shape[0]:
        k = order[i]
        if free[k]:
            i += 1
            continue
        at = fractions[k]
        reach = NOT_CLEARED
        cells_clear = not tables_read or _cells_clear(
            q0, q1, at, group_pairs, table_cells, table_offsets, table_variables, table_lows, inverse_steps,
            table_counts,
        )  # fmt: skip
        if bounded and cells_clear:
            _place_row(q0, q1, at, rows)
            last_stamp[0] += 1
            folded_link_poses(
                rows, 0, root, parents, origins, kinds, axes, variables, poses, frame, sines, cosines
            )
            for g in range(groups):
                place_point(poses, group_links[g], group_centers, g, group_world)
            wanted = min(
                max(fractions[count - 1] - at, at - fractions[0] if both_ways else 0.0), REACH_CAP / count
            )
            reach = _cleared_reach(
                wanted, at, margin, speeds, pair_speeds, slowness, pair_slowness, tables_read, known,
                known_at, candidates, candidate_pairs, last_stamp[0], poses, group_world, coarse_world,
                coarse_placed, group_links, group_radii, group_starts, group_stops, sphere_radii,
                coarse_local, box_rotations, box_centers, box_halves, box_kinds, low_x, low_y, low_z,
                high_x, high_y, high_z, unchecked, group_order, group_pairs, medium_local, medium_radii,
                medium_starts, medium_stops, medium_world, medium_placed,
            )  # fmt: skip
        if reach < 0.0:
            # Near an obstacle: this configuration and the next ones in order are checked in one
            # batch (a bound would fail there too), the batch growing while bounds keep failing.
            taken = 0
            while i < order.shape[0] and taken < batch:
                if not free[order[i]]:
                    batch_rows[taken] = order[i]
                    _place_row(q0, q1, fractions[order[i]], rows[taken:])
                    taken += 1
                i += 1
            valid = valid_rows(rows[:taken], arrays, margin, True, scratch)
            for m in range(taken):
                if not valid[m]:
                    return batch_rows[m], visited + m + 1
                free[batch_rows[m]] = True
            visited += taken
            batch = min(2 * batch, MAX_BATCH)
            continue
        visited += 1
        batch = FIRST_BATCH
        free[k] = True
        for direction in (1, -1):
            if direction < 0 and not both_ways:
                break
            other = k + direction
            while 0 <= other < count and not free[other] and abs(fractions[other] - at) <= reach:
                if tables_read and not _cells_clear(
                    q0, q1, fractions[other], group_pairs, table_cells, table_offsets, table_variables,
                    table_lows, inverse_steps, table_counts,
                ):  # fmt: skip
                    break
                free[other] = True
                other += direction
        i += 1
    return -1, visited


@numba.njit(cache=True)
def certified_segment_checked_in(
    q0: FloatArray,
    q1: FloatArray,
    intervals: int,
    check_start: bool,
    check_end: bool,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[bool, int]:
    """`segments.segment_checked_in`'s verdict: the endpoints asked for checked first, then the
    interior walked coarse to fine (a collision anywhere is met early), each bound proving free the
    configurations within its reach on both sides; configurations visited."""
    ends = int(check_start) + int(check_end)
    dimension = q0.shape[0]
    if ends:
        qs = np.empty((ends, dimension))
        row = 0
        if check_start:
            qs[row] = q0
            row += 1
        if check_end:
            qs[row] = q1
        valid = valid_rows(qs, arrays, margin, True, scratch)
        for m in range(ends):
            if not valid[m]:
                return False, m + 1
    fractions = coarse_to_fine_fractions(intervals)
    positions = np.empty(fractions.shape[0], dtype=np.int64)  # fraction rows by position, and visit order
    for i in range(fractions.shape[0]):
        positions[i] = round(fractions[i] * intervals) - 1
    ascending = np.empty(fractions.shape[0])
    for i in range(fractions.shape[0]):
        ascending[positions[i]] = fractions[i]
    first, visited = certified_walk(q0, q1, ascending, positions, True, arrays, margin, scratch)
    return first < 0, ends + visited


@numba.njit(cache=True)
def certified_free_prefix_checked_in(
    q0: FloatArray,
    q1: FloatArray,
    distance: float,
    resolution: float,
    arrays: ValidityArrays,
    margin: float,
    scratch: ValidityScratch,
) -> tuple[float, int]:
    """`segments.free_prefix_checked_in`'s free length (configurations at every multiple of
    ``resolution`` from q0, then q1), walked with clearance bounds; configurations visited."""
    steps = int(np.ceil(distance / resolution))
    count = max(steps - 1, 0) + 1
    lengths = np.empty(count)
    for k in range(count - 1):
        lengths[k] = float(k + 1) * resolution
    lengths[count - 1] = (distance / resolution) * resolution
    fractions = lengths / distance
    order = np.arange(count)
    first, visited = certified_walk(q0, q1, fractions, order, False, arrays, margin, scratch)
    if first < 0:
        return distance, visited
    return (lengths[first - 1] if first > 0 else 0.0), visited
