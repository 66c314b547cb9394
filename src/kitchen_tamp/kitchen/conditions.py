"""Conditions: states of boxes that geometry does not show (``clean``, ``cooked``).

A predicate the binding relates to ``condition`` is kept by the scene (``kitchen.conditions``):
the problem's ``:init`` sets the first ones, and an action whose skill succeeded sets and clears
the ones its effects name (a ``process`` skill checks where the box rests: in the sink to wash,
on a burner to cook). Ψ reads them back.
"""

from __future__ import annotations

from collections.abc import Iterable

from kitchen_tamp.kitchen.binding import DomainBinding
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.planning import Atom


def condition_predicates(binding: DomainBinding) -> frozenset[str]:
    """The predicates the binding keeps as conditions."""
    return frozenset(binding.predicates_for("condition"))


def conditions_among(binding: DomainBinding, atoms: Iterable[Atom]) -> set[Atom]:
    """The condition atoms among ``atoms``."""
    predicates = condition_predicates(binding)
    return {atom for atom in atoms if atom[0] in predicates}


def apply_condition_effects(kitchen: KitchenScene, added: Iterable[Atom], deleted: Iterable[Atom]) -> None:
    """Record what an action did to the conditions: its add effects set them, its delete effects
    clear them (other effects are geometry's)."""
    binding = kitchen.map.binding
    kitchen.conditions -= conditions_among(binding, deleted)
    kitchen.conditions |= conditions_among(binding, added)
