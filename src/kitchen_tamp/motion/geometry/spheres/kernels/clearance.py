"""The compiled clearance kernel of the sphere model: for M configurations at once, a smooth
penalty over every checked sphere pair closer than its influence distance, and its joint gradient.

Trajectory optimisation needs, at each of its collision points, one smooth number that says how
close the arm is to touching, and which way to move. The minimum over pairs is not smooth where
the closest pair changes; this kernel sums instead, as Drake's ``MinimumDistanceLowerBoundConstraint``
does, a smoothed hinge ``phi(x) = -x exp(1/x)`` (zero for ``x >= 0``, infinitely differentiable)
over every pair p, with ``x = (d_p - floor_p - width) / width``: a pair contributes only within
``width`` of its floor, and one pair exactly at its floor contributes ``phi(-1)``. The penalty
staying at most ``phi(-1)`` therefore implies every pair stays above its floor.

Pairs are those of `sphere_distances.SpherePairs`, in its order (sphere-box pairs, then
sphere-sphere pairs), so ``floors`` is indexed like its distances. Group bounding spheres skip
(group, box) and (group, group) pairs that are beyond every floor plus the width. Gradients are
analytic: each pair's unit direction of separation times its spheres' point Jacobians, summed per
sphere as a force and turned into joint rates (``axis . (centre - anchor) x force`` per revolute
joint the sphere's link depends on). Compiled by numba, cached on disk like `sphere_kernels`.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.codes import PRISMATIC, REVOLUTE
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import (
    aabb_gap,
    distance,
    link_poses,
    world_point,
)

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

@numba.njit(cache=True, fastmath=True, inline="always")
def _hinge(x: float) -> tuple[float, float]:
    """``phi(x) = -x exp(1/x)`` for x < 0, else 0, and its derivative ``exp(1/x) (1/x - 1)``."""
    if x >= 0.0:
        return 0.0, 0.0
    e = np.exp(1.0 / x)
    return -x * e, e * (1.0 / x - 1.0)


@numba.njit(cache=True, fastmath=True, inline="always")
def _box_gap_direction(
    point: FloatArray, rotation: FloatArray, center: FloatArray, half: FloatArray, direction: FloatArray
) -> float:
    """Signed distance from a point to an oriented box (negative inside), and in ``direction`` its
    world gradient with respect to the point (unit; the nearest face's normal inside)."""
    local = np.empty(3)
    clipped = np.zeros(3)
    outside = 0.0
    deepest, deepest_axis = -1e300, 0
    for axis in range(3):
        value = 0.0
        for k in range(3):
            value += rotation[k, axis] * (point[k] - center[k])
        local[axis] = value
        excess = abs(value) - half[axis]
        if excess > 0.0:
            outside += excess * excess
            clipped[axis] = excess if value >= 0.0 else -excess
        if excess > deepest:
            deepest, deepest_axis = excess, axis
    if outside > 0.0:
        gap = np.sqrt(outside)
        for k in range(3):
            direction[k] = (
                rotation[k, 0] * clipped[0] + rotation[k, 1] * clipped[1] + rotation[k, 2] * clipped[2]
            ) / gap
        return float(gap)
    sign = 1.0 if local[deepest_axis] >= 0.0 else -1.0
    for k in range(3):
        direction[k] = rotation[k, deepest_axis] * sign
    return float(deepest)


@numba.njit(cache=True, fastmath=True)
def clearance_penalties(
    qs: FloatArray,
    root: FloatArray,
    parents: IntArray,
    origins: FloatArray,
    kinds: IntArray,
    axes: FloatArray,
    variables: IntArray,
    depends: npt.NDArray[np.bool_],
    sphere_links: IntArray,
    sphere_centers: FloatArray,
    sphere_radii: FloatArray,
    group_links: IntArray,
    group_starts: IntArray,
    group_stops: IntArray,
    group_centers: FloatArray,
    group_radii: FloatArray,
    box_rotations: FloatArray,
    box_centers: FloatArray,
    box_halves: FloatArray,
    box_lows: FloatArray,
    box_highs: FloatArray,
    group_box_pairs: IntArray,
    box_pair_offsets: IntArray,
    group_pairs: IntArray,
    sphere_pair_offsets: IntArray,
    floors: FloatArray,
    width: float,
) -> tuple[FloatArray, FloatArray]:
    """Per row of ``qs`` (M, n): the summed hinge penalty (M,) and its gradient (M, n)."""
    count, dimension = qs.shape
    spheres, links = sphere_radii.shape[0], parents.shape[0]
    penalties = np.zeros(count)
    gradients = np.zeros((count, dimension))
    poses = np.empty((links, 4, 4))
    motion, frame = np.empty((4, 4)), np.empty((4, 4))
    world = np.empty((spheres, 3))
    placed = np.zeros(spheres, dtype=np.bool_)
    forces = np.zeros((spheres, 3))
    group_world = np.empty((group_radii.shape[0], 3))
    direction = np.empty(3)
    reach = width
    for p in range(floors.shape[0]):
        reach = max(reach, floors[p] + width)
    for m in range(count):
        link_poses(qs[m], root, parents, origins, kinds, axes, variables, poses, motion, frame)
        placed[:] = False
        forces[:] = 0.0
        total = 0.0
        for g in range(group_radii.shape[0]):
            world_point(poses[group_links[g]], group_centers[g], group_world[g])
        for k in range(group_box_pairs.shape[0]):
            g, b = group_box_pairs[k, 0], group_box_pairs[k, 1]
            if aabb_gap(group_world[g], box_lows[b], box_highs[b]) - group_radii[g] >= reach:
                continue
            for s in range(group_starts[g], group_stops[g]):
                if not placed[s]:
                    world_point(poses[sphere_links[s]], sphere_centers[s], world[s])
                    placed[s] = True
                gap = _box_gap_direction(world[s], box_rotations[b], box_centers[b], box_halves[b], direction)
                floor = floors[box_pair_offsets[k] + s - group_starts[g]]
                value, slope = _hinge((gap - sphere_radii[s] - floor - width) / width)
                if value == 0.0:
                    continue
                total += value
                for i in range(3):
                    forces[s, i] += slope / width * direction[i]
        for k in range(group_pairs.shape[0]):
            g, h = group_pairs[k, 0], group_pairs[k, 1]
            if distance(group_world[g], group_world[h]) - group_radii[g] - group_radii[h] >= reach:
                continue
            size = group_stops[h] - group_starts[h]
            row = sphere_pair_offsets[k] - group_starts[h]
            for s in range(group_starts[g], group_stops[g]):
                if not placed[s]:
                    world_point(poses[sphere_links[s]], sphere_centers[s], world[s])
                    placed[s] = True
                if distance(world[s], group_world[h]) - sphere_radii[s] - group_radii[h] >= reach:
                    continue
                for t in range(group_starts[h], group_stops[h]):
                    if not placed[t]:
                        world_point(poses[sphere_links[t]], sphere_centers[t], world[t])
                        placed[t] = True
                    length = distance(world[s], world[t])
                    floor = floors[row + (s - group_starts[g]) * size + t]
                    gap = length - sphere_radii[s] - sphere_radii[t]
                    value, slope = _hinge((gap - floor - width) / width)
                    if value == 0.0:
                        continue
                    total += value
                    scale = slope / width / max(length, 1e-12)
                    for i in range(3):
                        push = scale * (world[s, i] - world[t, i])
                        forces[s, i] += push
                        forces[t, i] -= push
        penalties[m] = total
        if total == 0.0:
            continue
        for link in range(links):
            j = variables[link]
            if j < 0 or kinds[link] == 0:
                continue
            # the joint's world axis and anchor: its link's pose applied to the local axis (a
            # rotation about the axis leaves it, and the link origin, where they were)
            axis_world = np.empty(3)
            for i in range(3):
                axis_world[i] = (
                    poses[link, i, 0] * axes[link, 0]
                    + poses[link, i, 1] * axes[link, 1]
                    + poses[link, i, 2] * axes[link, 2]
                )
            rate = 0.0
            for s in range(spheres):
                if not placed[s] or not depends[sphere_links[s], j]:
                    continue
                f = forces[s]
                if kinds[link] == REVOLUTE:
                    lever = world[s] - poses[link, :3, 3]
                    rate += axis_world[0] * (lever[1] * f[2] - lever[2] * f[1])
                    rate += axis_world[1] * (lever[2] * f[0] - lever[0] * f[2])
                    rate += axis_world[2] * (lever[0] * f[1] - lever[1] * f[0])
                elif kinds[link] == PRISMATIC:
                    rate += axis_world[0] * f[0] + axis_world[1] * f[1] + axis_world[2] * f[2]
            gradients[m, j] = rate
    return penalties, gradients


@numba.njit(cache=True)
def clearance_penalties_of_arguments(
    qs: FloatArray, arguments: tuple[Any, ...], floors: FloatArray, width: float
) -> tuple[FloatArray, FloatArray]:
    """`clearance_penalties` with the model's arrays (from ``root`` to ``sphere_pair_offsets``) as one
    tuple: what `kernels.loading` calls, and what the module compiled ahead of time exports (a wrapper,
    so that ``pycc`` compiles the kernel itself with its own flags: see `kernels.ahead_of_time`)."""
    return clearance_penalties(qs, *arguments, floors, width)  # type: ignore[call-arg]
