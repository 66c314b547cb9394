"""What each symbol of the kitchen domain is in the scene: bodies, links, joints, models.

This replaces the original project's table of hand-tuned joint angles: a symbol
maps to geometry (a surface or region link, a drawer's joint, floor and handle
links, a box model) and every joint goal is computed from that geometry. The map
is derived from the kitchen's scene file, like the model files it points to, so
the two cannot disagree; it carries the binding of the domain it is used with
(``kitchen_tamp.kitchen.binding``: the domain's types, predicates and actions in
kitchen terms).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from types import MappingProxyType
from typing import Final

from kitchen_tamp.kitchen.binding import DomainBinding
from kitchen_tamp.kitchen.binding_reader import read_binding
from kitchen_tamp.kitchen.scene.models import MOUNT_LINK, floor_link, handle_link, joint_name, model_files
from kitchen_tamp.kitchen.scene.spec import KitchenSpec, StartSpec
from kitchen_tamp.kitchen.scene.spec_reader import read_scene
from kitchen_tamp.shipped_kitchens import default_domain_path, default_scene_path

KITCHEN_BODY: Final = "kitchen"
ROBOT_BODY: Final = "panda"
ROBOT_MOUNT_LINK: Final = MOUNT_LINK
"""The robot's base stands at the centre of this link's top face."""


@dataclass(frozen=True)
class SurfaceSymbol:
    """A ``surface``: a box link of the kitchen whose top face boxes stand on."""

    link: str


@dataclass(frozen=True)
class RegionSymbol:
    """A ``region``: a thin slab link on a surface, of a kind a domain may give its own type."""

    link: str
    surface: str
    kind: str


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
    """A ``box``: a rigid box body loaded from its own URDF, and where the scene starts it."""

    urdf: Path
    start: StartSpec | None = None


@dataclass(frozen=True)
class KitchenMap:
    """Symbol -> geometry for every object the kitchen has, grouped by kind, and the binding
    of the domain the kitchen is used with."""

    scene_path: Path
    """The scene file this map (and the model files) came from."""
    kitchen_urdf: Path
    surfaces: MappingProxyType[str, SurfaceSymbol]
    openables: MappingProxyType[str, OpenableSymbol]
    boxes: MappingProxyType[str, BoxSymbol]
    binding: DomainBinding
    regions: MappingProxyType[str, RegionSymbol] = field(default_factory=lambda: MappingProxyType({}))

    def type_of(self, name: str) -> str | None:
        """The kind of a kitchen object (``surface``, ``region``, ``openable``, ``box``; see
        ``kitchen_tamp.kitchen.binding``), or None if the kitchen has no such object."""
        if name in self.surfaces:
            return "surface"
        if name in self.regions:
            return "region"
        if name in self.openables:
            return "openable"
        if name in self.boxes:
            return "box"
        return None

    def pddl_type_of(self, name: str) -> str | None:
        """The type the binding's domain gives a kitchen object, or None (no such object, or
        the domain has no type for its kind)."""
        kind = self.type_of(name)
        if kind is None:
            return None
        region = self.regions.get(name)
        return self.binding.pddl_type(kind, None if region is None else region.kind)

    def object_names(self) -> list[str]:
        """Every object of the kitchen: surfaces, regions, openables, boxes."""
        return [*self.surfaces, *self.regions, *self.openables, *self.boxes]

    def regions_on(self, surface: str) -> list[str]:
        """The regions on ``surface``."""
        return [name for name, region in self.regions.items() if region.surface == surface]


def kitchen_map_of(spec: KitchenSpec, binding: DomainBinding) -> KitchenMap:
    """The map of a kitchen read from its scene file, for a domain's binding; writes its model
    files (see ``scene_models.model_files``)."""
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
        boxes=MappingProxyType({b.name: BoxSymbol(files.boxes[b.name], b.start) for b in spec.boxes}),
        binding=binding,
        regions=MappingProxyType({r.name: RegionSymbol(r.name, r.surface, r.kind) for r in spec.regions}),
    )


def load_kitchen_map(scene_path: Path, domain_path: Path | None = None) -> KitchenMap:
    """Read a scene file and the binding of a domain (the shipped kitchen domain by default)
    and derive the map and models; ``SceneFileError`` / ``BindingFileError`` if a file is bad."""
    binding = read_binding(domain_path if domain_path is not None else default_domain_path())
    return kitchen_map_of(read_scene(scene_path), binding)


@cache
def default_kitchen_map() -> KitchenMap:
    """The map of the default kitchen (shipped with the package) for the shipped kitchen domain."""
    return load_kitchen_map(default_scene_path())
