"""Packed placements: when uniform samples in a region find no spot clear of what is already
there, poses flush against the region's edges and beside the boxes there (at the placement gap).

A packed pose is a corner fit: along each of the box's two flat axes it touches something -- a
region edge from inside, or another footprint from outside at its gap. The poses are tried in
an order that puts those touching the most first (a corner of the region before a spot
beside one box), shuffled per seed among equals, so the order is deterministic for a seed.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.abstraction import RESTING_GAP
from kitchen_tamp.kitchen.scene.regions import SupportRegion, box_corners
from kitchen_tamp.kitchen.skills.placements import Placement, Size, flat_axes, resting_rotation
from kitchen_tamp.world import FloatArray, Pose

CONTACT_SLACK: Final = 1e-4
"""A packed pose keeps this much beyond the gap, so round-off never makes it touch."""
TOUCH_DISTANCE: Final = 0.001
"""An edge or a footprint this near (beyond its gap) counts as touched, for the order."""
QUARTER_TURN: Final = np.pi / 2.0

Face = tuple[int, int]
"""A box face as (axis, sign)."""


@dataclass(frozen=True)
class Footprint:
    """Something a packed pose keeps clear of, in the region's frame: the corners of its
    outline in the plane, the directions of its edges, its height band and the gap to keep."""

    corners: FloatArray
    axes: tuple[FloatArray, FloatArray]
    heights: tuple[float, float]
    gap: float

    @property
    def yaw(self) -> float:
        """The direction of its first edge, modulo a quarter turn."""
        return float(np.arctan2(self.axes[0][1], self.axes[0][0]) % QUARTER_TURN)


def box_footprint(region: SupportRegion, world_from_box: Pose, size: Size, gap: float) -> Footprint:
    """A box's footprint in ``region``'s frame (its flat axes, or the region's when it is tilted)."""
    corners = np.array([region.local_point(c) for c in box_corners(world_from_box, size)])
    first, second = flat_axes((region.world_from_region.inverse() @ world_from_box).rotation)
    heights = (float(corners[:, 2].min()), float(corners[:, 2].max()))
    return Footprint(corners[:, :2], (first, second), heights, gap)


def region_footprint(region: SupportRegion, other: SupportRegion) -> Footprint:
    """Another region's rectangle in ``region``'s frame, kept clear of at any height."""
    hx, hy = other.half_size
    corners = np.array([
        region.local_point(other.world_from_region.apply((sx * hx, sy * hy, 0.0)))
        for sx in (-1, 1) for sy in (-1, 1)
    ])
    rotation = (region.world_from_region.inverse() @ other.world_from_region).rotation
    return Footprint(corners[:, :2], (rotation[:2, 0], rotation[:2, 1]), (-np.inf, np.inf), 0.0)


def packed_placements(
    region: SupportRegion,
    size: Size,
    faces: Sequence[Face],
    footprints: Sequence[Footprint],
    rng: np.random.Generator,
) -> list[Placement]:
    """Poses of a box with one of ``faces`` down, inside ``region``, clear of ``footprints`` by
    their gaps and flush against the region's edges or beside them; the most touching first,
    in an order shuffled by ``rng`` among equals."""
    hx, hy = region.half_size
    near = [f for f in footprints if _near(f, (hx, hy), 2.0 * max(size) + f.gap)]
    yaws = sorted({round((base + k * QUARTER_TURN) % (2.0 * np.pi), 9)
                   for base in (0.0, *(f.yaw for f in near)) for k in range(4)})
    touching: list[int] = []
    placements: list[Placement] = []
    for down_axis, down_sign in dict.fromkeys(faces):
        half = np.abs(resting_rotation(down_axis, down_sign, 0.0)) @ (np.array(size) / 2.0)
        band = (RESTING_GAP, RESTING_GAP + 2.0 * float(half[2]))
        standing = [f for f in near if f.heights[1] > band[0] and f.heights[0] < band[1]]
        for yaw in yaws:
            positions, contacts = _flush_positions((hx, hy), (float(half[0]), float(half[1])), yaw, standing)
            rotation = resting_rotation(down_axis, down_sign, yaw)
            for (x, y), count in zip(positions, contacts, strict=True):
                local = Pose.from_rotation((x, y, float(half[2]) + RESTING_GAP), rotation)
                world_from_box = region.world_from_region @ local
                placements.append(Placement(region.name, world_from_box, down_axis, down_sign))
                touching.append(int(count))
    order = sorted(rng.permutation(len(placements)), key=lambda i: -touching[i])
    return [placements[i] for i in order]


def _near(footprint: Footprint, half_size: tuple[float, float], reach: float) -> bool:
    """Whether a footprint comes within ``reach`` of the region's rectangle."""
    low, high = footprint.corners.min(axis=0), footprint.corners.max(axis=0)
    limit = np.array(half_size) + reach
    return bool(np.all(low <= limit) and np.all(high >= -limit))


def _flush_positions(
    half_size: tuple[float, float], half: tuple[float, float], yaw: float, footprints: Sequence[Footprint]
) -> tuple[FloatArray, FloatArray]:
    """The corner-fit centres (n, 2) of a footprint of half extents ``half`` turned by ``yaw``
    that lie inside the region and clear of ``footprints``, and how many things each touches."""
    u = np.array([np.cos(yaw), np.sin(yaw)])
    v = np.array([-np.sin(yaw), np.cos(yaw)])
    hx, hy = half_size
    region_corners = np.array([[sx * hx, sy * hy] for sx in (-1, 1) for sy in (-1, 1)])
    along_u = _contact_offsets(region_corners @ u, half[0], footprints, u)
    along_v = _contact_offsets(region_corners @ v, half[1], footprints, v)
    centres = (along_u[:, None, None] * u + along_v[None, :, None] * v).reshape(-1, 2)
    reach = half[0] * np.abs(u) + half[1] * np.abs(v)  # the footprint's half extents along x and y
    room = np.array([hx, hy]) - reach
    inside = np.all(np.abs(centres) <= room + 1e-9, axis=1)
    contacts = np.sum(np.abs(centres) >= room - TOUCH_DISTANCE, axis=1)
    for footprint in footprints:
        inside &= _separated(centres, half, (u, v), footprint, footprint.gap)
        apart = _separated(centres, half, (u, v), footprint, footprint.gap + TOUCH_DISTANCE)
        contacts += np.logical_not(apart)
    return centres[inside], contacts[inside]


def _contact_offsets(
    region_extent: FloatArray, half: float, footprints: Sequence[Footprint], direction: FloatArray
) -> FloatArray:
    """Centre offsets along ``direction`` that put the footprint flush against the region's
    edges (from inside) or beside each footprint (from outside, at its gap)."""
    offsets = [region_extent.min() + half, region_extent.max() - half]
    for footprint in footprints:
        extent = footprint.corners @ direction
        reach = half + footprint.gap + CONTACT_SLACK
        offsets += [extent.min() - reach, extent.max() + reach]
    return np.unique(np.round(offsets, 9))


def _separated(
    centres: FloatArray,
    half: tuple[float, float],
    own_axes: tuple[FloatArray, FloatArray],
    footprint: Footprint,
    margin: float,
) -> FloatArray:
    """Which footprints centred at ``centres`` stay at least ``margin`` from ``footprint``
    along some separating axis (their own or its edge directions)."""
    u, v = own_axes
    separated = np.zeros(len(centres), dtype=bool)
    for axis in (u, v, *footprint.axes):
        middle = centres @ axis
        radius = half[0] * abs(float(u @ axis)) + half[1] * abs(float(v @ axis))
        extent = footprint.corners @ axis
        separated |= (middle + radius + margin <= extent.min()) | (extent.max() + margin <= middle - radius)
    return separated
