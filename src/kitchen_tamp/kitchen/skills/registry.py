"""The skill registry: skill name -> sampler of motion targets; which skill an action is, and
which argument plays which role, the kitchen's binding says (``kitchen_tamp.kitchen.binding``)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from types import MappingProxyType
from typing import Protocol

import numpy as np

from kitchen_tamp.kitchen.binding import SKILL_ROLES, ActionBinding
from kitchen_tamp.kitchen.errors import UnknownActionError, UnknownObjectError
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.skills.open_drawer import sample_open
from kitchen_tamp.kitchen.skills.parameters import DEFAULT_PARAMETERS, SkillParameters
from kitchen_tamp.kitchen.skills.pick import sample_pick
from kitchen_tamp.kitchen.skills.place import sample_place
from kitchen_tamp.kitchen.skills.process import sample_process
from kitchen_tamp.kitchen.skills.targets import SkillTargets

Action = tuple[str, tuple[str, ...]]
SkillSampler = Callable[
    [KitchenScene, Action, ActionBinding, np.random.Generator, SkillParameters], SkillTargets
]


class GroundedAction(Protocol):
    """Anything with a name and arguments, e.g. ``kitchen_tamp.planning.GroundAction``."""

    @property
    def name(self) -> str: ...

    @property
    def args(self) -> tuple[str, ...]: ...


SKILLS: MappingProxyType[str, SkillSampler] = MappingProxyType(
    {
        "pick": sample_pick,
        "place": sample_place,
        "place_in": sample_place,
        "stack": sample_place,
        "open": sample_open,
        "process": sample_process,
    }
)
"""Skill name -> target sampler (the skills of ``binding.SKILL_ROLES``)."""


def check_arguments(kitchen: KitchenScene, binding: ActionBinding, args: Sequence[str]) -> None:
    """Raise ``UnknownObjectError`` for an argument the kitchen lacks, types differently from the
    action's parameter, or (a box) did not load, or whose kind its role cannot take."""
    name, kitchen_map = binding.action, kitchen.map
    for index, arg in enumerate(args):
        if kitchen_map.type_of(arg) is None:
            raise UnknownObjectError(arg, f"it is an argument of {name} but not a kitchen object")
        actual = kitchen_map.pddl_type_of(arg) or str(kitchen_map.type_of(arg))
        allowed = binding.parameter_types[index]
        if not kitchen_map.binding.accepts(actual, allowed):
            expected = " or ".join(sorted(allowed))
            raise UnknownObjectError(arg, f"{name} needs a {expected} here, {arg} is a {actual}")
        if kitchen_map.type_of(arg) == "box" and arg not in kitchen.boxes:
            raise UnknownObjectError(arg, "this problem did not put that box in the kitchen")
    roles = SKILL_ROLES[binding.skill]
    for role, index in binding.roles.items():
        kinds = roles.kinds(role) or ()
        if kitchen_map.type_of(args[index]) not in kinds:
            raise UnknownObjectError(
                args[index], f"{name}'s {role} must be a {' or '.join(kinds)}, {args[index]} is a "
                f"{kitchen_map.type_of(args[index])}"
            )


def sample_targets(
    kitchen: KitchenScene,
    name: str,
    args: Sequence[str],
    rng: np.random.Generator,
    parameters: SkillParameters = DEFAULT_PARAMETERS,
) -> SkillTargets:
    """Motion targets for the grounded action ``(name *args)`` in the scene as it is now.

    Raises ``UnknownActionError`` for an action the kitchen's binding does not bind,
    ``UnknownObjectError`` for an argument the kitchen lacks (or of the wrong
    type), and ``SkillFailure`` when no sample works.
    """
    binding = kitchen.map.binding.action(name)
    if binding is None:
        known = ", ".join(kitchen.map.binding.actions)
        raise UnknownActionError(f"no kitchen skill for action {name!r}; known: {known}")
    if len(args) != len(binding.parameter_types):
        count = len(binding.parameter_types)
        raise UnknownActionError(f"action {name!r} takes {count} arguments, got {len(args)}")
    check_arguments(kitchen, binding, args)
    return SKILLS[binding.skill](kitchen, (name, tuple(args)), binding, rng, parameters)


def sample_action_targets(
    kitchen: KitchenScene,
    action: GroundedAction,
    rng: np.random.Generator,
    parameters: SkillParameters = DEFAULT_PARAMETERS,
) -> SkillTargets:
    """``sample_targets`` for a planner's grounded action object."""
    return sample_targets(kitchen, action.name, action.args, rng, parameters)
