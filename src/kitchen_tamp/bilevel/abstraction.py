"""The abstract level: abstract states s, abstract actions a, the abstractor Psi and abstract plans.

Abstract states must be hashable (a set of atoms, a bitset, a room name): the
planners index them. Low-level states need not be.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import Generic, Protocol, TypeVar

import numpy as np

X = TypeVar("X")
S = TypeVar("S")
A = TypeVar("A")


@dataclass(frozen=True)
class AbstractTransition(Generic[S, A]):
    """One abstract step ``(s, a, s')``: what a trajectory sampler is asked to realise."""

    source: S
    action: A
    target: S


@dataclass(frozen=True)
class AbstractPlan(Generic[S, A]):
    """Abstract states ``s_0 .. s_n`` and the abstract actions ``a_0 .. a_{n-1}`` between them."""

    states: tuple[S, ...]
    actions: tuple[A, ...]

    def __post_init__(self) -> None:
        if len(self.states) != len(self.actions) + 1:
            raise ValueError(
                f"an abstract plan with {len(self.actions)} actions needs {len(self.actions) + 1} "
                f"states, got {len(self.states)}"
            )

    def __len__(self) -> int:
        return len(self.actions)

    @property
    def transitions(self) -> tuple[AbstractTransition[S, A], ...]:
        return tuple(
            AbstractTransition(self.states[i], action, self.states[i + 1])
            for i, action in enumerate(self.actions)
        )


@dataclass(frozen=True)
class Abstraction(Generic[X, S, A]):
    """How a problem looks from above.

    ``abstract_state`` is Psi(x) -> s; ``successors(s)`` yields the ``(a, s')``
    pairs of the abstract transition model, in a fixed order for a given ``s``;
    ``is_goal(s)`` is abstract goal checking; ``describe(s)`` is the text that
    failure messages show for an abstract state.
    """

    abstract_state: Callable[[X], S]
    successors: Callable[[S], Iterable[tuple[A, S]]]
    is_goal: Callable[[S], bool]
    describe: Callable[[S], str] = repr


class AbstractPlanGenerator(Protocol[S, A]):
    """Yields abstract plans from ``initial`` to a goal, best first, lazily.

    Equal candidates are ordered with ``rng``, so one seed gives one order.
    """

    def __call__(self, initial: S, rng: np.random.Generator) -> Iterator[AbstractPlan[S, A]]: ...
