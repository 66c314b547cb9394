"""What every search returns, and the bookkeeping they share."""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass
from itertools import pairwise
from typing import Literal, Protocol

from kitchen_tamp.planning.task import GroundAction, State, Task

SearchStatus = Literal["solved", "unsolvable", "failed", "budget"]
"""``unsolvable``: the reachable states were exhausted without a goal (a proof);
``failed``: an incomplete search (enforced hill climbing) gave up, which proves
nothing; ``budget``: time or expansions ran out."""


@dataclass(frozen=True, slots=True)
class SearchResult:
    """What a search found (``plan``, None without one), why it stopped, and what it cost."""

    planner: str
    status: SearchStatus
    plan: tuple[GroundAction, ...] | None
    expanded: int
    generated: int
    evaluated: int
    seconds: float
    message: str = ""

    @property
    def solved(self) -> bool:
        return self.status == "solved"


StateParents = Mapping[State, State | None]
"""Each reached state's parent (None at the root); the actions are recovered afterwards."""


def plan_to(task: Task, parents: StateParents, state: State) -> tuple[GroundAction, ...]:
    """The actions along the parent pointers from the root to ``state``.

    Searches keep only parent states, which is cheaper than a (state, action)
    pair per generated state. Each step takes the first action, in successor
    order, that leads from the parent to the child (usually the one that
    generated it; any such action gives the same states).
    """
    path = [state]
    parent = parents[state]
    while parent is not None:
        path.append(parent)
        parent = parents[parent]
    path.reverse()
    return tuple(task.action_between(a, b) for a, b in pairwise(path))


class RowLinks(Protocol):
    """Per row of a compiled search, an int (its parent row, -1 at the root; or its action)."""

    def __getitem__(self, row: int, /) -> int: ...


def plan_from_rows(task: Task, parents: RowLinks, actions: RowLinks,
                   goal_row: int) -> tuple[GroundAction, ...]:
    """The actions from the root to ``goal_row`` of a compiled search's rows (each evaluated state's row
    holds its parent row and the action that generated it), as ``plan_to`` recovers them."""
    steps: list[int] = []
    row = goal_row
    while parents[row] >= 0:
        steps.append(actions[row])
        row = parents[row]
    states = [task.initial_state]
    for action in reversed(steps):
        states.append(task.actions[action].apply(states[-1]))
    return tuple(task.action_between(a, b) for a, b in pairwise(states))


class SearchBudget:
    """Time and expansion limits; ``exhausted`` is cheap enough to call per expansion."""

    CLOCK_EVERY = 64
    """The clock is read every this many expansions."""

    def __init__(self, time_budget: float | None, max_expansions: int | None) -> None:
        if time_budget is not None and time_budget <= 0:
            raise ValueError("time budget must be positive")
        if max_expansions is not None and max_expansions <= 0:
            raise ValueError("max_expansions must be positive")
        self.start = time.perf_counter()
        self.deadline = None if time_budget is None else self.start + time_budget
        self.max_expansions = max_expansions

    def exhausted(self, expanded: int) -> bool:
        if self.max_expansions is not None and expanded >= self.max_expansions:
            return True
        return (self.deadline is not None and expanded % self.CLOCK_EVERY == 0
                and time.perf_counter() > self.deadline)

    def next_check(self, expanded: int) -> float:
        """After ``exhausted(expanded)`` said no: the next count at which it can say yes.

        Hot loops compare against this number and only call ``exhausted`` there.
        """
        limit = float("inf") if self.max_expansions is None else float(self.max_expansions)
        if self.deadline is not None:
            limit = min(limit, float((expanded // self.CLOCK_EVERY + 1) * self.CLOCK_EVERY))
        return limit

    def elapsed(self) -> float:
        return time.perf_counter() - self.start

    def describe(self) -> str:
        return "search budget exhausted (time or expansions) before a plan was found"
