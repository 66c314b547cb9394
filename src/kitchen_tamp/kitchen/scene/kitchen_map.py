"""What each symbol of the kitchen domain is in the scene: bodies, links, joints, models.

This replaces the original project's table of hand-tuned joint angles: a symbol
maps to geometry (a surface link, a drawer's joint, floor and handle links, a
box model) and every joint goal is computed from that geometry. The map is
derived from the kitchen's scene file, like the model files it points to, so
the two cannot disagree.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from pathlib import Path
from types import MappingProxyType
from typing import Final

from kitchen_tamp.kitchen.scene.models import MOUNT_LINK, floor_link, handle_link, joint_name, model_files
from kitchen_tamp.kitchen.scene.spec import KitchenSpec
from kitchen_tamp.kitchen.scene.spec_reader import read_scene
from kitchen_tamp.shipped_kitchens import default_scene_path

KITCHEN_BODY: Final = "kitchen"
ROBOT_BODY: Final = "panda"
ROBOT_MOUNT_LINK: Final = MOUNT_LINK
"""The robot's base stands at the centre of this link's top face."""


@dataclass(frozen=True)
class SurfaceSymbol:
    """A ``surface``: a box link of the kitchen whose top face boxes stand on."""

    link: str


@dataclass(frozen=True)
class OpenableSymbol:
    """An ``openable``: a tray on a prismatic joint, its floor and its handle links."""

    joint: str
    link: str
    floor_link: str
    handle_link: str
    opened_fraction: float = 0.5
    """``opened`` holds when the joint is beyond this fraction of its travel."""


@dataclass(frozen=True)
class BoxSymbol:
    """A ``box``: a rigid box body loaded from its own URDF."""

    urdf: Path


@dataclass(frozen=True)
class KitchenMap:
    """Symbol -> geometry for every object the kitchen has, grouped by PDDL type."""

    scene_path: Path
    """The scene file this map (and the model files) came from."""
    kitchen_urdf: Path
    surfaces: MappingProxyType[str, SurfaceSymbol]
    openables: MappingProxyType[str, OpenableSymbol]
    boxes: MappingProxyType[str, BoxSymbol]

    def type_of(self, name: str) -> str | None:
        """The PDDL type of a kitchen object, or None if the kitchen has no such object."""
        if name in self.surfaces:
            return "surface"
        if name in self.openables:
            return "openable"
        if name in self.boxes:
            return "box"
        return None

    def object_names(self) -> list[str]:
        """Every object of the kitchen: surfaces, openables, boxes."""
        return [*self.surfaces, *self.openables, *self.boxes]


def kitchen_map_of(spec: KitchenSpec) -> KitchenMap:
    """The map of a kitchen read from its scene file; writes its model files (see
    ``scene_models.model_files``)."""
    files = model_files(spec)
    return KitchenMap(
        scene_path=spec.path,
        kitchen_urdf=files.kitchen,
        surfaces=MappingProxyType({s.name: SurfaceSymbol(s.name) for s in spec.surfaces}),
        openables=MappingProxyType(
            {
                d.name: OpenableSymbol(joint_name(d.name), d.name, floor_link(d.name), handle_link(d.name))
                for d in spec.drawers
            }
        ),
        boxes=MappingProxyType({b.name: BoxSymbol(files.boxes[b.name]) for b in spec.boxes}),
    )


def load_kitchen_map(scene_path: Path) -> KitchenMap:
    """Read a scene file and derive its map and models; ``SceneFileError`` if the file is bad."""
    return kitchen_map_of(read_scene(scene_path))


@cache
def default_kitchen_map() -> KitchenMap:
    """The map of the default kitchen (shipped with the package)."""
    return load_kitchen_map(default_scene_path())
