"""What every search returns, and the bookkeeping they share."""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from kitchen_tamp.planning.task import GroundAction, State

SearchStatus = Literal["solved", "unsolvable", "failed", "budget"]
"""``unsolvable``: the reachable states were exhausted without a goal (a proof);
``failed``: an incomplete search (enforced hill climbing) gave up, which proves
nothing; ``budget``: time or expansions ran out."""


@dataclass(frozen=True)
class SearchResult:
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


Parents = Mapping[State, tuple[State, GroundAction] | None]


def extract_plan(parents: Parents, state: State) -> tuple[GroundAction, ...]:
    """Follow parent pointers from ``state`` back to the root (whose entry is None)."""
    steps: list[GroundAction] = []
    entry = parents[state]
    while entry is not None:
        state, action = entry
        steps.append(action)
        entry = parents[state]
    steps.reverse()
    return tuple(steps)


class SearchBudget:
    """Time and expansion limits; ``exhausted`` is cheap enough to call per expansion."""

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
        return (self.deadline is not None and expanded % 64 == 0
                and time.perf_counter() > self.deadline)

    def elapsed(self) -> float:
        return time.perf_counter() - self.start

    def describe(self) -> str:
        return "search budget exhausted (time or expansions) before a plan was found"
