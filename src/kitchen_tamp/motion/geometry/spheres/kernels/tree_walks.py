"""Searching the sphere model's bounding-sphere trees in compiled code: a link's tight spheres
against one box, or two links' against each other, opening only bounds that come closer than the
margin; and placing spheres in the world once per configuration.

Used by the validity kernel (`sphere_kernels`), whose docstring describes the layout: arrays with
row indices, never rows, inlined by LLVM (``forceinline``); spheres are placed at most once per
configuration (a stamp per sphere says when it was last placed).
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.primitives import (
    box_gap_at,
    place_point,
    point_box_gap,
    points_apart,
)

FloatArray = npt.NDArray[np.float64]

STACK_DEPTH = 256
"""Room for pending nodes (or node pairs) of one tree traversal; the trees are far shallower."""


@numba.njit(cache=True, fastmath=True, forceinline=True)
def place_once(
    index: int,
    poses: FloatArray,
    links: npt.NDArray[np.int64],
    local: FloatArray,
    world: FloatArray,
    placed: npt.NDArray[np.int64],
    stamp: int,
) -> None:
    """World position of a sphere or bound, computed once per configuration: ``placed`` holds the
    stamp of the configuration each was last placed for (no clearing between configurations)."""
    if placed[index] != stamp:
        place_point(poses, links[index], local, index, world)
        placed[index] = stamp


@numba.njit(cache=True, fastmath=True, forceinline=True)
def place_span(
    poses: FloatArray, link: int, local: FloatArray, world: FloatArray, first: int, last: int
) -> None:
    """World centres (x, y and z rows of ``world``) of the points ``first:last`` of ``local``, all
    on ``link``: one SIMD pass."""
    r00, r01, r02, t0 = poses[link, 0, 0], poses[link, 0, 1], poses[link, 0, 2], poses[link, 0, 3]
    r10, r11, r12, t1 = poses[link, 1, 0], poses[link, 1, 1], poses[link, 1, 2], poses[link, 1, 3]
    r20, r21, r22, t2 = poses[link, 2, 0], poses[link, 2, 1], poses[link, 2, 2], poses[link, 2, 3]
    for signed in range(first, last):
        s = np.uint64(signed)  # unsigned: no negative-index wraparound, so contiguous lanes
        x, y, z = local[0, s], local[1, s], local[2, s]
        world[0, s] = r00 * x + r01 * y + r02 * z + t0
        world[1, s] = r10 * x + r11 * y + r12 * z + t1
        world[2, s] = r20 * x + r21 * y + r22 * z + t2


@numba.njit(cache=True, fastmath=True, forceinline=True)
def place_span_once(
    key: int,
    placed: npt.NDArray[np.int64],
    stamp: int,
    poses: FloatArray,
    link: int,
    local: FloatArray,
    world: FloatArray,
    first: int,
    last: int,
) -> None:
    """`_place_span`, skipped when ``placed[key]`` shows it done for this configuration's stamp
    (a tree leaf's spheres, or a group's coarse spheres)."""
    if placed[key] != stamp:
        place_span(poses, link, local, world, first, last)
        placed[key] = stamp


@numba.njit(cache=True, fastmath=True, forceinline=True)
def span_near_bound(
    first: int,
    last: int,
    margin: float,
    radii: FloatArray,
    world: FloatArray,
    bound: FloatArray,
    b: int,
    bound_radius: float,
) -> int:
    """How many spheres of ``first:last`` (centres in the x, y and z rows of ``world``) come within
    the margin of the sphere ``bound[b]`` of radius ``bound_radius``: one branch-free SIMD pass."""
    x, y, z = bound[b, 0], bound[b, 1], bound[b, 2]
    near = 0
    for signed in range(first, last):
        s = np.uint64(signed)  # unsigned: no negative-index wraparound, so contiguous lanes
        dx, dy, dz = world[0, s] - x, world[1, s] - y, world[2, s] - z
        reach = radii[s] + bound_radius + margin
        near += (reach > 0.0) & (dx * dx + dy * dy + dz * dz < reach * reach)
    return near


@numba.njit(cache=True, fastmath=True, forceinline=True)
def spans_touch(
    first_a: int,
    last_a: int,
    first_b: int,
    last_b: int,
    margin: float,
    radii: FloatArray,
    world: FloatArray,
    bound: FloatArray,
    b: int,
    bound_radius: float,
) -> bool:
    """Whether a sphere of ``first_a:last_a`` comes closer than the margin to one of
    ``first_b:last_b`` (centres in the x, y and z rows of ``world``), the second span held in the
    sphere ``bound[b]`` of radius ``bound_radius``: per sphere of the first span that comes that
    close to the bound, one branch-free SIMD pass over the second."""
    for s in range(first_a, last_a):
        x, y, z = world[0, s], world[1, s], world[2, s]
        reach_s = radii[s] + margin
        bx, by, bz = bound[b, 0] - x, bound[b, 1] - y, bound[b, 2] - z
        reach_bound = reach_s + bound_radius
        if reach_bound <= 0.0 or bx * bx + by * by + bz * bz >= reach_bound * reach_bound:
            continue
        touching = 0
        for signed in range(first_b, last_b):
            t = np.uint64(signed)  # unsigned: no negative-index wraparound, so contiguous lanes
            dx, dy, dz = world[0, t] - x, world[1, t] - y, world[2, t] - z
            reach = reach_s + radii[t]
            touching += (reach > 0.0) & (dx * dx + dy * dy + dz * dz < reach * reach)
        if touching:
            return True
    return False


@numba.njit(cache=True, fastmath=True, forceinline=True)
def tree_hits_box(
    root: int,
    b: int,
    poses: FloatArray,
    margin: float,
    node_links: npt.NDArray[np.int64],
    node_centers: FloatArray,
    node_radii: FloatArray,
    node_children: npt.NDArray[np.int64],
    node_first: npt.NDArray[np.int64],
    node_last: npt.NDArray[np.int64],
    node_world: FloatArray,
    node_placed: npt.NDArray[np.int64],
    sphere_local: FloatArray,
    sphere_radii: FloatArray,
    sphere_world: FloatArray,
    leaf_placed: npt.NDArray[np.int64],
    box_rotations: FloatArray,
    box_centers: FloatArray,
    box_halves: FloatArray,
    box_kinds: npt.NDArray[np.int64],
    stack: npt.NDArray[np.int64],
    stamp: int,
) -> bool:
    """Whether a sphere under node ``root`` comes closer than the margin to box ``b``: bounds are
    opened only when they come that close."""
    top = 0
    stack[0] = root
    while top >= 0:
        n = stack[top]
        top -= 1
        place_once(n, poses, node_links, node_centers, node_world, node_placed, stamp)
        gap = point_box_gap(node_world, n, box_rotations, box_centers, box_halves, box_kinds, b)
        if gap - node_radii[n] >= margin:
            continue
        if node_children[n, 0] < 0:
            place_span_once(
                n,
                leaf_placed,
                stamp,
                poses,
                node_links[n],
                sphere_local,
                sphere_world,
                node_first[n],
                node_last[n],
            )
            for s in range(node_first[n], node_last[n]):
                x, y, z = sphere_world[0, s], sphere_world[1, s], sphere_world[2, s]
                gap = box_gap_at(x, y, z, box_rotations, box_centers, box_halves, box_kinds, b)
                if gap - sphere_radii[s] < margin:
                    return True
            continue
        stack[top + 1] = node_children[n, 0]
        stack[top + 2] = node_children[n, 1]
        top += 2
    return False


@numba.njit(cache=True, fastmath=True, forceinline=True)
def trees_touch(
    root_a: int,
    root_b: int,
    poses: FloatArray,
    margin: float,
    node_links: npt.NDArray[np.int64],
    node_centers: FloatArray,
    node_radii: FloatArray,
    node_children: npt.NDArray[np.int64],
    node_first: npt.NDArray[np.int64],
    node_last: npt.NDArray[np.int64],
    node_world: FloatArray,
    node_placed: npt.NDArray[np.int64],
    sphere_local: FloatArray,
    sphere_radii: FloatArray,
    sphere_world: FloatArray,
    leaf_placed: npt.NDArray[np.int64],
    stack: npt.NDArray[np.int64],
    stamp: int,
) -> bool:
    """Whether a sphere under node ``root_a`` comes closer than the margin to one under ``root_b``:
    pairs of bounds that come that close are opened, the larger first."""
    top = 0
    stack[0], stack[1] = root_a, root_b
    while top >= 0:
        a, b = stack[2 * top], stack[2 * top + 1]
        top -= 1
        place_once(a, poses, node_links, node_centers, node_world, node_placed, stamp)
        place_once(b, poses, node_links, node_centers, node_world, node_placed, stamp)
        if points_apart(node_world, a, node_world, b, node_radii[a] + node_radii[b] + margin):
            continue
        leaf_a, leaf_b = node_children[a, 0] < 0, node_children[b, 0] < 0
        if leaf_a and leaf_b:
            for leaf in (a, b):
                place_span_once(
                    leaf,
                    leaf_placed,
                    stamp,
                    poses,
                    node_links[leaf],
                    sphere_local,
                    sphere_world,
                    node_first[leaf],
                    node_last[leaf],
                )
            if spans_touch(
                node_first[a],
                node_last[a],
                node_first[b],
                node_last[b],
                margin,
                sphere_radii,
                sphere_world,
                node_world,
                b,
                node_radii[b],
            ):
                return True
            continue
        if leaf_b or (not leaf_a and node_radii[a] >= node_radii[b]):
            for child in range(2):
                top += 1
                stack[2 * top], stack[2 * top + 1] = node_children[a, child], b
        else:
            for child in range(2):
                top += 1
                stack[2 * top], stack[2 * top + 1] = a, node_children[b, child]
    return False
