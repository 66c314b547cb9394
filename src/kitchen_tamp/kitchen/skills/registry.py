"""The skill registry: action name -> sampler of motion targets for a grounded action."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from types import MappingProxyType
from typing import Protocol

import numpy as np

from kitchen_tamp.kitchen.errors import UnknownActionError, UnknownObjectError
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.skills.open_drawer import sample_open
from kitchen_tamp.kitchen.skills.parameters import DEFAULT_PARAMETERS, SkillParameters
from kitchen_tamp.kitchen.skills.pick import sample_pick
from kitchen_tamp.kitchen.skills.place import sample_place
from kitchen_tamp.kitchen.skills.targets import SkillTargets

Action = tuple[str, tuple[str, ...]]
SkillSampler = Callable[[KitchenScene, Action, np.random.Generator, SkillParameters], SkillTargets]


class GroundedAction(Protocol):
    """Anything with a name and arguments, e.g. ``kitchen_tamp.planning.GroundAction``."""

    @property
    def name(self) -> str: ...

    @property
    def args(self) -> tuple[str, ...]: ...


def _pick(
    kitchen: KitchenScene, action: Action, rng: np.random.Generator, params: SkillParameters
) -> SkillTargets:
    box, support = action[1]
    return sample_pick(kitchen, action, box, support, rng, params)


def _place(
    kitchen: KitchenScene, action: Action, rng: np.random.Generator, params: SkillParameters
) -> SkillTargets:
    box, target = action[1]
    return sample_place(kitchen, action, box, target, rng, params)


def _open(
    kitchen: KitchenScene, action: Action, rng: np.random.Generator, params: SkillParameters
) -> SkillTargets:
    (openable,) = action[1]
    return sample_open(kitchen, action, openable, rng, params)


SKILL_SIGNATURES: MappingProxyType[str, tuple[str, ...]] = MappingProxyType(
    {
        "open": ("openable",),
        "pickUp": ("box", "surface"),
        "cabPickUp": ("box", "openable"),
        "placeOn": ("box", "surface"),
        "placeIn": ("box", "openable"),
    }
)
"""Parameter types of each action, as in the domain."""

SKILLS: MappingProxyType[str, SkillSampler] = MappingProxyType(
    {"open": _open, "pickUp": _pick, "cabPickUp": _pick, "placeOn": _place, "placeIn": _place}
)
"""Action name -> target sampler."""


def sample_targets(
    kitchen: KitchenScene,
    name: str,
    args: Sequence[str],
    rng: np.random.Generator,
    parameters: SkillParameters = DEFAULT_PARAMETERS,
) -> SkillTargets:
    """Motion targets for the grounded action ``(name *args)`` in the scene as it is now.

    Raises ``UnknownActionError`` for an action no skill implements,
    ``UnknownObjectError`` for an argument the kitchen lacks (or of the wrong
    type), and ``SkillFailure`` when no sample works.
    """
    if name not in SKILLS:
        raise UnknownActionError(f"no kitchen skill for action {name!r}; known: {', '.join(SKILLS)}")
    types = SKILL_SIGNATURES[name]
    if len(args) != len(types):
        raise UnknownActionError(f"action {name!r} takes {len(types)} arguments, got {len(args)}")
    for arg, expected in zip(args, types, strict=True):
        actual = kitchen.map.type_of(arg)
        if actual is None:
            raise UnknownObjectError(arg, f"it is an argument of {name} but not a kitchen object")
        if actual != expected:
            raise UnknownObjectError(arg, f"{name} needs a {expected} here, {arg} is a {actual}")
        if actual == "box" and arg not in kitchen.boxes:
            raise UnknownObjectError(arg, "this problem did not put that box in the kitchen")
    return SKILLS[name](kitchen, (name, tuple(args)), rng, parameters)


def sample_action_targets(
    kitchen: KitchenScene,
    action: GroundedAction,
    rng: np.random.Generator,
    parameters: SkillParameters = DEFAULT_PARAMETERS,
) -> SkillTargets:
    """``sample_targets`` for a planner's grounded action object."""
    return sample_targets(kitchen, action.name, action.args, rng, parameters)
