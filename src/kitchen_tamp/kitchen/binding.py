"""What a domain's symbols mean in the kitchen, as data: the binding of a domain.

A kitchen has objects of four kinds: ``surface`` (a block whose face objects stand on),
``region`` (a named part of a surface: a plate, a tray, a sink, a burner), ``openable`` (a
drawer) and ``box`` (a movable box). A domain names them with its own types, relates them with
its own predicates and acts on them with its own actions; its binding (a TOML file beside the
domain, read by ``binding_reader``) says

- which PDDL type each kind (and each region kind, e.g. ``sink``) has (``types``);
- which geometric relation each predicate is: Ψ derives every atom from one of ``RELATIONS``
  (``predicates``);
- which skill carries out each action and which parameter plays which of the skill's roles
  (``actions``; the skills and their roles are ``SKILL_ROLES``).

No code matches an action or predicate name: the skills and Ψ read this record.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Final

KINDS: Final = ("surface", "region", "openable", "box")
"""The kinds of kitchen objects."""
PLACES: Final = ("surface", "region")
SUPPORTS: Final = ("surface", "region", "openable", "box")

RELATIONS: Final = MappingProxyType(
    {
        "holding": ("box",),
        "hand_empty": (),
        "on_surface": ("box", "surface"),
        "on_region": ("box", "region"),
        "on_box": ("box", "box"),
        "in_drawer": ("box", "openable"),
        "surface_clear": ("surface",),
        "region_clear": ("region",),
        "drawer_clear": ("openable",),
        "box_clear": ("box",),
        "opened": ("openable",),
        "condition": ("box",),
    }
)
"""Relation -> the kinds of its arguments. ``holding``: the box rides with the hand;
``hand_empty``: nothing does; ``on_surface`` / ``on_region`` / ``on_box`` / ``in_drawer``: a
loose box rests on that support (its centre over the support's face, its bottom on it; a box on
a region is on the region, not on the region's surface); ``*_clear``: no box rests there (on a
surface: neither on it nor on its regions); ``opened``: the drawer is open past its threshold;
``condition``: a state geometry does not show (``clean``, ``cooked``), set by the actions whose
effects name it and kept with the scene (``kitchen_tamp.kitchen.conditions``)."""


@dataclass(frozen=True)
class SkillRoles:
    """The roles a skill's arguments play: role -> the kinds its object may be."""

    required: Mapping[str, tuple[str, ...]]
    optional: Mapping[str, tuple[str, ...]] = field(default_factory=lambda: MappingProxyType({}))

    def kinds(self, role: str) -> tuple[str, ...] | None:
        """The kinds ``role`` accepts, or None if the skill has no such role."""
        return self.required.get(role, self.optional.get(role))

    @property
    def names(self) -> tuple[str, ...]:
        return (*self.required, *self.optional)


SKILL_ROLES: Final = MappingProxyType(
    {
        "pick": SkillRoles(MappingProxyType({"object": ("box",)}), MappingProxyType({"support": SUPPORTS})),
        "place": SkillRoles(MappingProxyType({"object": ("box",), "support": PLACES})),
        "place_in": SkillRoles(MappingProxyType({"object": ("box",), "drawer": ("openable",)})),
        "stack": SkillRoles(MappingProxyType({"object": ("box",), "base": ("box",)})),
        "open": SkillRoles(MappingProxyType({"drawer": ("openable",)})),
        "process": SkillRoles(MappingProxyType({"object": ("box",), "place": PLACES})),
    }
)
"""Skill -> its roles. ``pick``: grasp the object where it rests (on ``support`` if the action
names it) and lift it; ``place``: put the held object down on a surface or region among what is
there; ``place_in``: into an open drawer; ``stack``: onto the top face of ``base``; ``open``: pull
the drawer open by its handle; ``process``: no motion, the object must rest on ``place`` (wash
in a sink, cook on a burner; the action's effects set its conditions)."""


@dataclass(frozen=True)
class ActionBinding:
    """One action: its skill, which parameter (by position) plays each role, and the types
    the domain declares for each parameter."""

    action: str
    skill: str
    roles: Mapping[str, int]
    parameter_types: tuple[frozenset[str], ...]

    def argument(self, role: str, args: Sequence[str]) -> str | None:
        """The argument playing ``role`` in a grounded action, or None if no parameter does."""
        index = self.roles.get(role)
        return None if index is None else args[index]


@dataclass(frozen=True)
class DomainBinding:
    """A domain's binding to the kitchen (see the module's description)."""

    path: Path
    """The binding file."""
    domain: str
    types: Mapping[str, str]
    """Kind (or region kind) -> PDDL type."""
    type_ancestors: Mapping[str, frozenset[str]]
    """PDDL type -> itself and every type above it."""
    predicates: Mapping[str, tuple[str, ...]]
    """Predicate -> the relations it is true for (each of the predicate's arity)."""
    actions: Mapping[str, ActionBinding]

    def pddl_type(self, kind: str, region_kind: str | None = None) -> str | None:
        """The domain's type of an object of ``kind`` (a region's own kind first), or None if
        the domain has no type for it."""
        if kind == "region" and region_kind is not None and region_kind in self.types:
            return self.types[region_kind]
        return self.types.get(kind)

    def accepts(self, pddl_type: str, allowed: frozenset[str]) -> bool:
        """Whether an object of ``pddl_type`` may be a parameter declared with ``allowed`` types."""
        return bool(self.type_ancestors.get(pddl_type, frozenset({pddl_type})) & allowed)

    def action(self, name: str) -> ActionBinding | None:
        """The binding of an action (PDDL names are case-insensitive)."""
        found = self.actions.get(name)
        if found is None:
            found = next((b for n, b in self.actions.items() if n.lower() == name.lower()), None)
        return found

    def predicates_for(self, relation: str) -> tuple[str, ...]:
        """The predicates that hold for ``relation``."""
        return tuple(p for p, relations in self.predicates.items() if relation in relations)
