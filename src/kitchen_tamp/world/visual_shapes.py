"""What a body looks like: the visual geometry and colours its URDF gave PyBullet.

Other viewers (the browser replay) draw a scene from these, so they show the same
primitives, meshes and colours as the simulator loaded, posed per link.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import pybullet as p

from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.transforms import Pose


class VisualKind(Enum):
    """The URDF geometry element of a visual."""

    BOX = "box"
    SPHERE = "sphere"
    CYLINDER = "cylinder"
    CAPSULE = "capsule"
    MESH = "mesh"


_KINDS = {
    p.GEOM_BOX: VisualKind.BOX,
    p.GEOM_SPHERE: VisualKind.SPHERE,
    p.GEOM_CYLINDER: VisualKind.CYLINDER,
    p.GEOM_CAPSULE: VisualKind.CAPSULE,
    p.GEOM_MESH: VisualKind.MESH,
}


@dataclass(frozen=True)
class VisualShape:
    """One ``<visual>`` of a link, in the link's URDF frame.

    ``size`` is the box's full extents; for a sphere (radius, -, -); for a cylinder or
    a capsule (length, radius, -); for a mesh its scale per axis.
    """

    link: str
    kind: VisualKind
    size: tuple[float, float, float]
    link_from_visual: Pose
    rgba: tuple[float, float, float, float]
    mesh_path: str | None = None


def visual_shapes(body: Body) -> tuple[VisualShape, ...]:
    """Every visual of every link of ``body``, in the order PyBullet reports them."""
    shapes = []
    for data in p.getVisualShapeData(body.uid, physicsClientId=body.client):
        link_index, geometry, dimensions, mesh_file, position, quaternion, rgba = data[1:8]
        kind = _KINDS.get(geometry)
        if kind is None:
            continue
        mesh = mesh_file.decode() if kind is VisualKind.MESH else None
        shapes.append(
            VisualShape(
                link=body.link_name(link_index),
                kind=kind,
                size=(float(dimensions[0]), float(dimensions[1]), float(dimensions[2])),
                link_from_visual=Pose.from_parts(position, quaternion),
                rgba=(float(rgba[0]), float(rgba[1]), float(rgba[2]), float(rgba[3])),
                mesh_path=mesh,
            )
        )
    return tuple(shapes)
