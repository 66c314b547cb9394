"""Searches by name: the one place the command line, the benchmarks and the tests look them up.

A new search is a function with the ``Search`` signature (a task, a time
budget, an expansion limit; a ``SearchResult`` back) and one line in
``SEARCHES`` with its description in ``SEARCH_DESCRIPTIONS``; the command
line's ``--planner`` choices follow from them.
"""

from __future__ import annotations

from typing import Protocol

from kitchen_tamp.planning.search.best_first import astar_search, greedy_best_first_search
from kitchen_tamp.planning.search.breadth_first import breadth_first_search
from kitchen_tamp.planning.search.enforced_hill_climbing import enforced_hill_climbing
from kitchen_tamp.planning.search.result import SearchResult
from kitchen_tamp.planning.task import Task


class Search(Protocol):
    def __call__(
        self, task: Task, *, time_budget: float | None = None, max_expansions: int | None = None
    ) -> SearchResult: ...


SEARCHES: dict[str, Search] = {
    "bfs": breadth_first_search,
    "ehc": enforced_hill_climbing,
    "gbfs": greedy_best_first_search,
    "astar": astar_search,
}
"""Name -> search with its default settings. ``bfs`` and ``astar`` (with LM-cut) return shortest plans."""

SEARCH_DESCRIPTIONS: dict[str, str] = {
    "bfs": "breadth-first search (optimal)",
    "ehc": "enforced hill climbing with h_FF, helpful actions first",
    "gbfs": "greedy best-first search with h_FF, lazy; all, preferred and novel successors in turn",
    "astar": "A* with LM-cut (optimal)",
}


def plan(task: Task, planner: str = "bfs", *, time_budget: float | None = None,
         max_expansions: int | None = None) -> SearchResult:
    """Run the named search on ``task``."""
    try:
        search = SEARCHES[planner]
    except KeyError:
        raise ValueError(f"unknown planner {planner!r}; choose from {', '.join(SEARCHES)}") from None
    return search(task, time_budget=time_budget, max_expansions=max_expansions)
