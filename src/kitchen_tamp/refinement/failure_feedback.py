"""What a failed skill teaches the abstract search, as facts of ``kitchen_tamp.bilevel.feedback``.

* A skill that failed as ``obstructed`` names boxes; once confirmed (the skill finds
  targets with the fewest of them moved out of the scene,
  ``kitchen.skills.obstructions``), the action is learned to need them gone from where
  they are: an ``Obstruction`` whose atoms are the confirmed boxes' location atoms in
  the abstract state the action was sampled from (``on``/``in`` atoms, as the binding
  names the relations ``on_surface``, ``on_region``, ``on_box``, ``in_drawer``). The next
  abstract plan moves them first.
* A placement (``place``, ``place_in``) that failed as ``unreachable`` is checked with
  every other box moved out; if it still finds nothing, and the empty hand reaches no pose
  above the place either (the grasp may be to blame, not the place), its place is out of
  reach, and every placement onto that place is pruned (``Unreachable``), learned once:
  reach is the arm's, whatever it holds.

A box is never blamed for the failure of an action on a box that was itself confirmed in
its way (the learned preconditions would then ask each to be moved before the other,
and no abstract plan would be left): the check keeps it in the scene, and finds another
set of boxes, or none. Confirmations are kept, so a step sampled again from the same
abstract state costs no second check; they draw from this object's own generator, never
the planner's.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Final

import numpy as np

from kitchen_tamp.bilevel.feedback import ActionKey, Obstruction, Unreachable
from kitchen_tamp.kitchen import FailureKind, KitchenScene, SkillFailure
from kitchen_tamp.kitchen.skills.obstructions import confirm_obstruction, confirm_unreachable
from kitchen_tamp.planning import GroundAction, State, Task

LOCATION_RELATIONS: Final = ("on_surface", "on_region", "on_box", "in_drawer")
"""The relations that say where a box is: an obstruction is learned as these atoms' absence."""
PLACEMENT_SKILLS: Final = {"place": "support", "place_in": "drawer"}
"""The skills whose place can be out of reach, and the role that names the place."""


@dataclass
class FailureFeedback:
    """Turns the skill failures of one planning run into learned facts."""

    kitchen: KitchenScene
    task: Task
    rng: np.random.Generator
    obstructions: dict[tuple[ActionKey, State], tuple[Obstruction, ...]] = field(default_factory=dict)
    unreachable: dict[str, tuple[Unreachable, ...]] = field(default_factory=dict)
    in_the_way: dict[str, set[str]] = field(default_factory=dict)
    """Box -> the boxes confirmed in the way of an action on it."""
    confirmations: int = 0
    """Checks run (a skill sampled again with boxes moved out)."""

    def facts(self, action: GroundAction, source: State, failure: SkillFailure) -> tuple[object, ...]:
        """The facts ``failure`` of ``action``, sampled in the scene as it is now (whose abstract
        state is ``source``), teaches; () when it teaches nothing confirmed."""
        if failure.kind is FailureKind.OBSTRUCTED and failure.objects:
            key = ((action.name, action.args), source)
            if key not in self.obstructions:
                self.obstructions[key] = self._obstruction(action, source, failure)
            return self.obstructions[key]
        place = self._placement_target(action)
        if failure.kind is FailureKind.UNREACHABLE and place is not None:
            if place not in self.unreachable:
                self.unreachable[place] = self._unreachable(action, place)
            return self.unreachable[place]
        return ()

    def _placement_target(self, action: GroundAction) -> str | None:
        """Where ``action`` puts its box down, if its skill is a placement onto a fixed place."""
        binding = self.kitchen.map.binding.action(action.name)
        if binding is None or binding.skill not in PLACEMENT_SKILLS:
            return None
        return binding.argument(PLACEMENT_SKILLS[binding.skill], action.args)

    def _obstruction(
        self, action: GroundAction, source: State, failure: SkillFailure
    ) -> tuple[Obstruction, ...]:
        self.confirmations += 1
        bound = self.kitchen.map.binding.action(action.name)
        subject = None if bound is None else bound.argument("object", action.args)
        keep = {box for box, blockers in self.in_the_way.items() if subject in blockers}
        blockers = confirm_obstruction(self.kitchen, action, failure, self.rng, keep=keep)
        if subject is not None:
            self.in_the_way.setdefault(subject, set()).update(blockers)
        binding = self.kitchen.map.binding
        predicates = {p for relation in LOCATION_RELATIONS for p in binding.predicates_for(relation)}
        absent = frozenset(atom for atom in self.task.state_atoms(source)
                           if atom[0] in predicates and len(atom) > 1 and atom[1] in blockers)
        if not blockers or not absent:
            return ()
        return (Obstruction((action.name, action.args), absent, blockers),)

    def _unreachable(self, action: GroundAction, place: str) -> tuple[Unreachable, ...]:
        self.confirmations += 1
        if not confirm_unreachable(self.kitchen, action, self.rng, place):
            return ()
        pruned = frozenset((candidate.name, candidate.args) for candidate in self.task.actions
                           if self._placement_target(candidate) == place)
        return (Unreachable(place, pruned),)
