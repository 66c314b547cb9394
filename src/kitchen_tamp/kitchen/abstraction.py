"""Ψ: the symbolic state of the kitchen computed from geometry.

A box is on a surface (in a drawer) when it is not held, its centre lies over
the region and its lowest corner rests on the region's face; a drawer is
``opened`` past a fraction of its travel; ``surfClear``/``cabClear`` hold when
no box rests there; ``armClear`` when nothing is attached to the hand.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.errors import InitialStateMismatchError
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.regions import SupportRegion, box_corners
from kitchen_tamp.planning import Atom, atom_text

RESTING_GAP: Final = 0.001
"""Boxes are put down this far above a face, so resting is not a collision."""
RESTING_TOLERANCE: Final = 0.005
"""A box rests on a face when its lowest corner is within this height of it."""


def rests_on(kitchen: KitchenScene, box: str, region: SupportRegion) -> bool:
    """Whether ``box`` stands on ``region`` (centre over it, bottom on its face)."""
    world_from_box = kitchen.box(box).base_pose()
    bottom = float(np.min(box_corners(world_from_box, kitchen.box_size(box))[:, 2]))
    return region.contains_xy(world_from_box.translation) and abs(bottom - region.top_z) <= RESTING_TOLERANCE


def abstract_state(kitchen: KitchenScene, objects: Iterable[str] | None = None) -> frozenset[Atom]:
    """Ψ(scene): every true atom about ``objects`` (all loaded kitchen objects by default)."""
    names = set(objects) if objects is not None else None

    def known(name: str) -> bool:
        return names is None or name in names

    surfaces = [s for s in kitchen.map.surfaces if known(s)]
    openables = [o for o in kitchen.map.openables if known(o)]
    boxes = [b for b in kitchen.boxes if known(b)]
    held = kitchen.held_box()
    atoms: set[Atom] = set()
    if held is not None and known(held):
        atoms.add(("holding", held))
    if held is None:
        atoms.add(("armClear",))
    loose = [b for b in boxes if b != held]
    for surface in surfaces:
        region = kitchen.surface_region(surface)
        on = [b for b in loose if rests_on(kitchen, b, region)]
        atoms.update(("boxOn", b, surface) for b in on)
        if not on:
            atoms.add(("surfClear", surface))
    for openable in openables:
        region = kitchen.openable_region(openable)
        inside = [b for b in loose if rests_on(kitchen, b, region)]
        atoms.update(("boxIn", b, openable) for b in inside)
        if not inside:
            atoms.add(("cabClear", openable))
        if kitchen.is_opened(openable):
            atoms.add(("opened", openable))
    return frozenset(atoms)


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
