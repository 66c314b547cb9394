"""Stable placements of a box in a support region, sampled from geometry, and the test of a
placement against the boxes (and regions) already there."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.abstraction import RESTING_GAP
from kitchen_tamp.kitchen.scene.regions import SupportRegion, box_corners
from kitchen_tamp.world import FloatArray, Pose, rotation_about_axis

Size = tuple[float, float, float]


@dataclass(frozen=True)
class Placement:
    """A resting pose of a box: one face down on the region, inside it."""

    region: str
    world_from_box: Pose
    down_axis: int
    down_sign: int


def resting_rotation(down_axis: int, down_sign: int, yaw: float) -> FloatArray:
    """region_from_box rotation that puts the box face ``down_sign * axis`` down, turned by yaw."""
    down = down_sign * np.eye(3)[down_axis]
    target = np.array([0.0, 0.0, -1.0])
    axis = np.cross(down, target)
    if np.linalg.norm(axis) < 1e-9:
        tilt = np.eye(3) if np.dot(down, target) > 0 else rotation_about_axis([1.0, 0.0, 0.0], np.pi)
    else:
        tilt = rotation_about_axis(axis, float(np.arccos(np.clip(np.dot(down, target), -1.0, 1.0))))
    return rotation_about_axis([0.0, 0.0, 1.0], yaw) @ tilt


def sample_placement(
    region: SupportRegion,
    size: tuple[float, float, float],
    rng: np.random.Generator,
    preferred_down: Sequence[tuple[tuple[int, int], float]],
    centre_inset: float | None = None,
) -> Placement | None:
    """A random stable pose of a box inside ``region``, or None if it cannot fit.

    ``preferred_down`` lists box faces (axis, sign) to put down with their
    probabilities; with the remaining probability any of the six faces is
    chosen. Position and yaw are uniform over the poses whose footprint lies
    inside the region -- or, with ``centre_inset`` (stacking on a box's top face), whose
    centre lies that far inside it: the box may overhang, its centre of mass is over the face.
    """
    draw = rng.random()
    face = None
    for candidate, probability in preferred_down:
        if draw < probability:
            face = candidate
            break
        draw -= probability
    if face is None:
        face = (int(rng.integers(3)), int(rng.choice([-1, 1])))
    down_axis, down_sign = face
    yaw = rng.uniform(0.0, 2.0 * np.pi)
    region_from_box_rotation = resting_rotation(down_axis, down_sign, yaw)
    half_extents = np.abs(region_from_box_rotation) @ (np.array(size) / 2.0)
    hx, hy = region.half_size
    if centre_inset is None:
        room = np.array([hx - half_extents[0], hy - half_extents[1]])
    else:
        room = np.array([hx - centre_inset, hy - centre_inset])
    if np.any(room < 0.0):
        return None
    local = np.array(
        [rng.uniform(-room[0], room[0]), rng.uniform(-room[1], room[1]), half_extents[2] + RESTING_GAP]
    )
    region_from_box = Pose.from_rotation(local, region_from_box_rotation)
    return Placement(region.name, region.world_from_region @ region_from_box, down_axis, down_sign)


FIT_YAW_STEPS = 361
"""Yaws, from 0 to 90 degrees, at which ``fits_somewhere`` tries a footprint (a quarter degree apart)."""


def fits_somewhere(region: SupportRegion, size: Size, centre_inset: float | None = None) -> bool:
    """Whether some face down and some yaw put the box's footprint inside ``region`` (or, with
    ``centre_inset``, its centre that far inside it), as ``sample_placement`` requires; yaws are
    tried a quarter degree apart, so a box that fits only within a narrower window of yaw is
    said not to fit."""
    hx, hy = region.half_size
    if centre_inset is not None:
        return min(hx, hy) >= centre_inset
    yaw = np.linspace(0.0, np.pi / 2.0, FIT_YAW_STEPS)
    cos, sin = np.cos(yaw), np.sin(yaw)
    for down_axis in range(3):
        a, b = (size[i] / 2.0 for i in range(3) if i != down_axis)
        fits = (a * cos + b * sin <= hx) & (a * sin + b * cos <= hy)
        if fits.any():
            return True
    return False


def down_face(world_from_box: Pose) -> tuple[int, int]:
    """(axis, sign) of the box face that points most downwards."""
    return face_along(world_from_box.rotation.T @ np.array([0.0, 0.0, -1.0]))


def face_along(direction_in_box: FloatArray) -> tuple[int, int]:
    """(axis, sign) of the box face whose normal is closest to a box-frame direction."""
    axis = int(np.argmax(np.abs(direction_in_box)))
    return axis, int(np.sign(direction_in_box[axis]))


def flat_axes(rotation: FloatArray) -> list[FloatArray]:
    """The two box axes that lie flat (a box resting on a face), else the world's x and y."""
    flat = [i for i in range(3) if abs(rotation[2, i]) < 0.5]
    axes = [rotation[:2, i] / np.linalg.norm(rotation[:2, i]) for i in flat]
    return axes if len(axes) == 2 else [np.array([1.0, 0.0]), np.array([0.0, 1.0])]


def footprints_overlap(
    points_a: FloatArray, axes_a: Sequence[FloatArray], points_b: FloatArray, axes_b: Sequence[FloatArray],
    margin: float,
) -> bool:
    """Whether two convex footprints (their corner points in the plane and edge directions)
    come closer than ``margin`` (separating axes)."""
    for axis in (*axes_a, *axes_b):
        a, b = points_a @ axis, points_b @ axis
        if a.max() + margin <= b.min() or b.max() + margin <= a.min():
            return False
    return True


def boxes_overlap(
    world_from_a: Pose, size_a: Size, world_from_b: Pose, size_b: Size, margin: float
) -> bool:
    """Whether two boxes share height and their footprints come closer than ``margin``."""
    corners_a, corners_b = box_corners(world_from_a, size_a), box_corners(world_from_b, size_b)
    if corners_a[:, 2].max() <= corners_b[:, 2].min() or corners_b[:, 2].max() <= corners_a[:, 2].min():
        return False
    return footprints_overlap(
        corners_a[:, :2], flat_axes(world_from_a.rotation),
        corners_b[:, :2], flat_axes(world_from_b.rotation), margin,
    )


def overlaps_region(world_from_box: Pose, size: Size, region: SupportRegion) -> bool:
    """Whether a box's footprint reaches over a region's rectangle."""
    hx, hy = region.half_size
    frame = region.world_from_region
    corners = np.array([frame.apply((sx * hx, sy * hy, 0.0)) for sx in (-1, 1) for sy in (-1, 1)])
    axes = [region.world_from_region.rotation[:2, i] for i in range(2)]
    points = box_corners(world_from_box, size)[:, :2]
    return footprints_overlap(points, flat_axes(world_from_box.rotation), corners[:, :2], axes, 0.0)
