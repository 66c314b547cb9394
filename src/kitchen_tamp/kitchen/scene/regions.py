"""Regions of the kitchen computed from geometry: where boxes may stand (a link's top face, or
the face of a box that points up)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.world import Body, FloatArray, Pose


@dataclass(frozen=True)
class SupportRegion:
    """The top face of a box link: a rectangle in a frame at its centre, z pointing up."""

    name: str
    world_from_region: Pose
    half_size: tuple[float, float]
    ceiling_z: float
    """Height a carried box's bottom must clear to leave the region (walls, for a drawer)."""

    @property
    def top_z(self) -> float:
        """World height of the supporting face."""
        return self.world_from_region.position[2]

    def local_point(self, world_point: FloatArray) -> FloatArray:
        """A world point expressed in the region frame."""
        return self.world_from_region.inverse().apply(world_point)

    def contains_xy(self, world_point: FloatArray, inset: float = 0.0) -> bool:
        """Whether a point lies above (or below) the rectangle shrunk by ``inset``."""
        local = self.local_point(world_point)
        hx, hy = self.half_size
        return bool(abs(local[0]) <= hx - inset and abs(local[1]) <= hy - inset)


def support_region(body: Body, link: str, name: str, ceiling_link: str | None = None) -> SupportRegion:
    """The region on top of ``link``'s single box shape, at the body's current configuration.

    ``ceiling_link`` (e.g. the drawer with its walls) sets ``ceiling_z`` to that
    link's top; otherwise the region's own top.
    """
    shapes = body.box_shapes(link)
    if len(shapes) != 1:
        raise ValueError(f"link {link!r} of {body.name!r} should be one box, has {len(shapes)} shapes")
    shape = shapes[0]
    world_from_shape = body.link_com_pose(link) @ shape.com_from_box
    world_from_region = world_from_shape @ Pose((0.0, 0.0, shape.size[2] / 2.0))
    if world_from_region.rotation[2, 2] < 0.999:
        raise ValueError(f"link {link!r} of {body.name!r} is not level, it cannot support boxes")
    ceiling = world_from_region.position[2]
    if ceiling_link is not None:
        ceiling = max(ceiling, float(body.aabb(ceiling_link)[1][2]))
    return SupportRegion(name, world_from_region, (shape.size[0] / 2.0, shape.size[1] / 2.0), ceiling)


def top_face(world_from_box: Pose, size: tuple[float, float, float], name: str) -> SupportRegion:
    """The face of a box that points up, as the region another box may be stacked on (its
    ceiling is the face itself)."""
    rotation = world_from_box.rotation
    up = int(np.argmax(np.abs(rotation[2, :])))
    sign = 1.0 if rotation[2, up] > 0.0 else -1.0
    first, second = (i for i in range(3) if i != up)
    x_axis, y_axis = rotation[:, first], rotation[:, second] * sign
    z_axis = sign * rotation[:, up]
    if float(np.dot(np.cross(x_axis, y_axis), z_axis)) < 0.0:
        y_axis = -y_axis
    centre = world_from_box.translation + z_axis * size[up] / 2.0
    face = Pose.from_rotation(centre, np.column_stack([x_axis, y_axis, z_axis]))
    return SupportRegion(name, face, (size[first] / 2.0, size[second] / 2.0), float(centre[2]))


def box_size(body: Body) -> tuple[float, float, float]:
    """Size of a box body's single box shape."""
    shapes = body.box_shapes(body.base_link_name)
    if len(shapes) != 1:
        raise ValueError(f"body {body.name!r} is not a single box")
    return shapes[0].size


_CORNER_SIGNS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
"""The signs of the eight corners of a box centred on its origin (times its half size)."""


def box_corners(world_from_box: Pose, size: tuple[float, float, float]) -> FloatArray:
    """The eight corners (8, 3) of a box in the world."""
    half = np.array(size) / 2.0
    rotation, translation = world_from_box.rotation, world_from_box.translation
    return np.array([rotation @ (signs * half) + translation for signs in _CORNER_SIGNS])
