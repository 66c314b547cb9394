"""Ψ: the symbolic state of the kitchen computed from geometry.

Geometry gives relations (``kitchen_tamp.kitchen.binding.RELATIONS``); the domain's binding
says which predicate each relation is. A loose box rests on a support (a surface, a region, a
drawer's floor, another box's top face) when its centre lies over the support's face and its
lowest corner on it: its centre of mass is then over what holds it up, so it stands. A box on a
region rests on the region, not on the region's surface. A drawer is ``opened`` past a fraction
of its travel; a place is clear when no box rests there; a box is clear when it is not held and
no box rests on it; the hand is empty when nothing is attached to it; conditions (``clean``,
``cooked``) are the scene's record of what actions did (``kitchen.conditions``).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.errors import InitialStateMismatchError
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.regions import SupportRegion, box_corners
from kitchen_tamp.planning import Atom, atom_text
from kitchen_tamp.world.transforms import FloatArray

RESTING_GAP: Final = 0.001
"""Boxes are put down this far above a face, so resting is not a collision."""
RESTING_TOLERANCE: Final = 0.005
"""A box rests on a face when its lowest corner is within this height of it."""
RESTING_RELATIONS: Final = {
    "surface": "on_surface", "region": "on_region", "openable": "in_drawer", "box": "on_box"
}
"""The kind of support a box rests on -> the relation."""


@dataclass(frozen=True)
class _Footing:
    """Where a loose box stands: its centre and the height of its lowest corner."""

    centre: FloatArray
    bottom: float

    def on(self, region: SupportRegion) -> bool:
        return region.contains_xy(self.centre) and abs(self.bottom - region.top_z) <= RESTING_TOLERANCE


def _footing(kitchen: KitchenScene, box: str) -> _Footing:
    world_from_box = kitchen.box(box).base_pose()
    bottom = float(np.min(box_corners(world_from_box, kitchen.box_size(box))[:, 2]))
    return _Footing(world_from_box.translation, bottom)


def rests_on(kitchen: KitchenScene, box: str, region: SupportRegion) -> bool:
    """Whether ``box`` stands on ``region`` (centre over it, bottom on its face)."""
    return _footing(kitchen, box).on(region)


@dataclass
class Relations:
    """The relations that hold in the scene now: relation -> argument tuples."""

    facts: dict[str, set[tuple[str, ...]]] = field(default_factory=dict)

    def add(self, relation: str, *args: str) -> None:
        self.facts.setdefault(relation, set()).add(args)

    def of(self, relation: str) -> set[tuple[str, ...]]:
        return self.facts.get(relation, set())


Support = tuple[str, str, SupportRegion]
"""(kind, name, face) of something a box may rest on: a kind of ``RESTING_RELATIONS``."""


def _supports(kitchen: KitchenScene) -> list[Support]:
    """Every support of the scene now, held box excluded: surfaces, regions, openables, box tops."""
    kitchen_map = kitchen.map
    held = kitchen.held_box()
    return [
        *(("surface", name, kitchen.surface_region(name)) for name in kitchen_map.surfaces),
        *(("region", name, kitchen.region_region(name)) for name in kitchen_map.regions),
        *(("openable", name, kitchen.openable_region(name)) for name in kitchen_map.openables),
        *(("box", name, kitchen.box_top(name)) for name in kitchen.boxes if name != held),
    ]


def supports_of(
    kitchen: KitchenScene, box: str, supports: list[Support] | None = None
) -> list[tuple[str, str]]:
    """(kind, name) of everything ``box`` rests on now (at most one, unless the scene is odd);
    ``supports``: the scene's (``_supports``), when the caller has them already."""
    footing = _footing(kitchen, box)
    return [
        (kind, name)
        for kind, name, face in (supports if supports is not None else _supports(kitchen))
        if not (kind == "box" and name == box) and footing.on(face)
    ]


def scene_relations(kitchen: KitchenScene) -> Relations:
    """Every relation of the scene (see the module's description)."""
    relations = Relations()
    kitchen_map = kitchen.map
    held = kitchen.held_box()
    if held is None:
        relations.add("hand_empty")
    else:
        relations.add("holding", held)
    occupied: set[str] = set()
    scene_supports = _supports(kitchen)  # one face per support, not one per box and support
    for box in kitchen.boxes:
        if box == held:
            continue
        supports = supports_of(kitchen, box, scene_supports)
        on_region = {name for kind, name in supports if kind == "region"}
        region_surfaces = {kitchen_map.regions[name].surface for name in on_region}
        for kind, name in supports:
            if kind == "surface" and name in region_surfaces:
                continue  # a box on a plate is on the plate, not on the table under it
            relation = RESTING_RELATIONS[kind]
            relations.add(relation, box, name)
            occupied.add(name)
        occupied |= region_surfaces
    for surface in kitchen_map.surfaces:
        if surface not in occupied:
            relations.add("surface_clear", surface)
    for region in kitchen_map.regions:
        if region not in occupied:
            relations.add("region_clear", region)
    for openable in kitchen_map.openables:
        if openable not in occupied:
            relations.add("drawer_clear", openable)
        if kitchen.is_opened(openable):
            relations.add("opened", openable)
    for box in kitchen.boxes:
        if box != held and box not in occupied:
            relations.add("box_clear", box)
    return relations


def abstract_state(kitchen: KitchenScene, objects: Iterable[str] | None = None) -> frozenset[Atom]:
    """Ψ(scene): every true atom about ``objects`` (all loaded kitchen objects by default), in the
    predicates of the kitchen's binding."""
    names = set(objects) if objects is not None else None
    relations = scene_relations(kitchen)
    atoms: set[Atom] = set()
    for predicate, meanings in kitchen.map.binding.predicates.items():
        for relation in meanings:
            if relation == "condition":
                atoms.update(a for a in kitchen.conditions if a[0] == predicate)
                continue
            atoms.update((predicate, *args) for args in relations.of(relation))
    if names is None:
        return frozenset(atoms)
    return frozenset(a for a in atoms if all(arg in names for arg in a[1:]))


def check_initial_state(
    kitchen: KitchenScene, objects: Mapping[str, str], init_atoms: frozenset[Atom]
) -> None:
    """Raise ``InitialStateMismatchError`` unless Ψ(scene) equals ``init_atoms``."""
    abstract = abstract_state(kitchen, objects)
    if abstract != init_atoms:
        raise InitialStateMismatchError(
            missing=sorted(atom_text(a) for a in init_atoms - abstract),
            unexpected=sorted(atom_text(a) for a in abstract - init_atoms),
        )
