"""Conditions: states of boxes that geometry does not show (``clean``, ``cooked``).

A predicate the binding relates to ``condition`` is kept by the scene (``kitchen.conditions``):
the problem's ``:init`` sets the first ones, and an action whose skill succeeded sets and clears
the ones its effects name (a ``process`` skill checks where the box rests: in the sink to wash,
on a burner to cook). Ψ reads them back.

The planner, the kinematic judge and physics derive them by one rule, ``record_conditions``:
after an action, its condition effects hold if its skill's requirement holds in the scene
(for ``process``: its object rests, loose, on its place), from the domain, the binding and
the geometry -- never from what a trajectory file says.
"""

from __future__ import annotations

from collections.abc import Iterable

from kitchen_tamp.kitchen.abstraction import supports_of
from kitchen_tamp.kitchen.binding import DomainBinding
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.planning import Atom, GroundAction, Task


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


def process_problem(kitchen: KitchenScene, box: str, place: str) -> str | None:
    """Why a ``process`` skill cannot act on ``box`` at ``place`` now (the hand holds it, or it
    does not rest on the place), or None."""
    if kitchen.held_box() == box:
        return f"the hand holds {box}: it must rest on {place}"
    resting = [name for _, name in supports_of(kitchen, box)]
    if place not in resting:
        return f"{box} rests on {' and '.join(resting) or 'nothing'}, not on {place}"
    return None


def record_conditions(kitchen: KitchenScene, task: Task, action: GroundAction) -> str | None:
    """After ``action`` of ``task``: record its condition effects if its skill's requirement
    holds in the scene as it is; else leave the conditions as they are and return why."""
    binding = kitchen.map.binding.action(action.name)
    if binding is not None and binding.skill == "process":
        box, place = binding.argument("object", action.args), binding.argument("place", action.args)
        problem = None if box is None or place is None else process_problem(kitchen, box, place)
        if problem is not None:
            return f"{action.text} sets no conditions: {problem}"
    atoms = task.atoms
    deleted = (atoms[i] for i in range(len(atoms)) if action.delete >> i & 1)
    apply_condition_effects(kitchen, (atoms[i] for i in action.add_ids), deleted)
    return None
