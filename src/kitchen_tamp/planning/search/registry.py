"""Searches by name: the one place the CLI and the benchmarks look them up."""

from __future__ import annotations

from kitchen_tamp.planning.search.result import SearchResult
from kitchen_tamp.planning.task import Task

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from typing import Protocol

    class Search(Protocol):
        def __call__(
            self, task: Task, *, time_budget: float | None = None, max_expansions: int | None = None
        ) -> SearchResult: ...


# Each search's module is imported when it first runs: a planner process pays only for the one it uses.

def breadth_first_search(task: Task, *, time_budget: float | None = None,
                         max_expansions: int | None = None) -> SearchResult:
    from kitchen_tamp.planning.search import breadth_first

    return breadth_first.breadth_first_search(task, time_budget=time_budget, max_expansions=max_expansions)


def enforced_hill_climbing(task: Task, *, time_budget: float | None = None,
                           max_expansions: int | None = None) -> SearchResult:
    from kitchen_tamp.planning.search import enforced_hill_climbing as ehc

    return ehc.enforced_hill_climbing(task, time_budget=time_budget, max_expansions=max_expansions)


def greedy_best_first_search(task: Task, *, time_budget: float | None = None,
                             max_expansions: int | None = None) -> SearchResult:
    from kitchen_tamp.planning.search import best_first

    return best_first.greedy_best_first_search(task, time_budget=time_budget, max_expansions=max_expansions)


def astar_search(task: Task, *, time_budget: float | None = None,
                 max_expansions: int | None = None) -> SearchResult:
    from kitchen_tamp.planning.search import best_first

    return best_first.astar_search(task, time_budget=time_budget, max_expansions=max_expansions)


SEARCHES: dict[str, Search] = {
    "bfs": breadth_first_search,
    "ehc": enforced_hill_climbing,
    "gbfs": greedy_best_first_search,
    "astar": astar_search,
}
"""Name -> search with its default settings. ``bfs`` and ``astar`` (with h_max) return shortest plans."""

SEARCH_DESCRIPTIONS: dict[str, str] = {
    "bfs": "breadth-first search (optimal)",
    "ehc": "enforced hill climbing with h_FF, helpful actions first",
    "gbfs": "greedy best-first search with h_FF, preferred and all successors in turn",
    "astar": "A* with h_max (optimal)",
}


def plan(task: Task, planner: str = "bfs", *, time_budget: float | None = None,
         max_expansions: int | None = None) -> SearchResult:
    """Run the named search on ``task``."""
    try:
        search = SEARCHES[planner]
    except KeyError:
        raise ValueError(f"unknown planner {planner!r}; choose from {', '.join(SEARCHES)}") from None
    return search(task, time_budget=time_budget, max_expansions=max_expansions)
