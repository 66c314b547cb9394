"""Failures that come back to the abstract level: facts a sampler learned from a failure, and
the plan generators that take them into account.

A trajectory sampler that fails may say *why* in terms of the abstraction: a
``SamplingFailure`` carries ``feedback``, a tuple of facts. SeSamE hands them to a
plan generator that can learn (``LearningPlanGenerator``); when the generator learns
something new and the plan being refined no longer fits what it knows, the plan is
dropped at once (no backtracking over a plan known to be infeasible), and the next
abstract plans come from the generator's updated model. This is the interface layer
of Srivastava et al., "Combined Task and Motion Planning Through an Extensible
Planner-Independent Interface Layer" (ICRA 2014): a geometric failure becomes a
symbolic fact, and the task planner plans again with it.

The two facts of relational abstractions (``relational``'s generator learns them):

* ``Obstruction``: an action is feasible only where none of some atoms hold (the atoms
  that place the objects in its way where they are now), a learned negative
  precondition -- the next plan moves the obstruction first;
* ``Unreachable``: no sample reaches the targets of some actions, whatever else is
  where -- they are pruned from the task, learned once.

The generic loop knows facts only as objects; a generator that does not learn ignores them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol, TypeVar, runtime_checkable

from kitchen_tamp.bilevel.abstraction import AbstractPlan, AbstractPlanGenerator
from kitchen_tamp.planning import Atom, atom_text

S = TypeVar("S")
A = TypeVar("A")

ActionKey = tuple[str, tuple[str, ...]]
"""A ground action by name and arguments, e.g. ``("pick", ("red_box", "table"))``."""


@dataclass(frozen=True)
class Obstruction:
    """``action`` is feasible only where none of ``absent`` holds: the objects ``blockers`` were
    in its way, and ``absent`` are the atoms that located them there."""

    action: ActionKey
    absent: frozenset[Atom]
    blockers: tuple[str, ...]

    @property
    def text(self) -> str:
        name, args = self.action
        where = " ".join(atom_text(atom) for atom in sorted(self.absent))
        return f"{atom_text((name, *args))} is obstructed by {', '.join(self.blockers)} while {where}"


@dataclass(frozen=True)
class Unreachable:
    """No sample reaches the targets of ``actions`` (their ``place``): pruned from the task."""

    place: str
    actions: frozenset[ActionKey]

    @property
    def text(self) -> str:
        return f"{self.place} is out of reach: {len(self.actions)} action(s) pruned"


LearnedFact = Obstruction | Unreachable


def fact_text(fact: object) -> str:
    """A learned fact in words (any object: its ``text`` if it has one)."""
    text = getattr(fact, "text", None)
    return text if isinstance(text, str) else repr(fact)


@runtime_checkable
class LearningPlanGenerator(AbstractPlanGenerator[S, A], Protocol[S, A]):
    """A plan generator that takes facts learned from failures into account: plans it yields
    after ``learn`` returned new facts respect them."""

    def learn(self, facts: Sequence[object]) -> list[object]:
        """Take ``facts`` in; return those it did not know (and understands)."""
        ...

    def admits(self, plan: AbstractPlan[S, A]) -> bool:
        """Whether ``plan`` is still a plan under everything learned so far."""
        ...
