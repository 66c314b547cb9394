"""Searches by name: the one place the CLI and the benchmarks look them up."""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from typing import Protocol

    from kitchen_tamp.planning.search.result import SearchResult
    from kitchen_tamp.planning.task import Task

    class Search(Protocol):
        def __call__(
            self, task: Task, *, time_budget: float | None = None, max_expansions: int | None = None
        ) -> SearchResult: ...


SEARCH_PACKAGE = "kitchen_tamp.planning.search"


def _imported_when_run(module: str, name: str) -> Search:
    """The search ``name`` of ``kitchen_tamp.planning.search.module``, its module imported at its first run.

    A planner process then pays only for the searches it uses (``bfs`` never
    loads the heuristics).
    """
    def search(task: Task, *, time_budget: float | None = None,
               max_expansions: int | None = None) -> SearchResult:
        function: Search = getattr(importlib.import_module(f"{SEARCH_PACKAGE}.{module}"), name)
        return function(task, time_budget=time_budget, max_expansions=max_expansions)

    search.__name__ = search.__qualname__ = name
    return search


SEARCHES: dict[str, Search] = {
    "bfs": _imported_when_run("breadth_first", "breadth_first_search"),
    "ehc": _imported_when_run("enforced_hill_climbing", "enforced_hill_climbing"),
    "gbfs": _imported_when_run("best_first", "greedy_best_first_search"),
    "astar": _imported_when_run("best_first", "astar_search"),
}
"""Name -> search with its default settings. ``bfs`` and ``astar`` (with h_max) return shortest plans."""

SEARCH_DESCRIPTIONS: dict[str, str] = {
    "bfs": "breadth-first search (optimal)",
    "ehc": "enforced hill climbing with h_FF, helpful actions first",
    "gbfs": "greedy best-first search with h_FF, lazy; all, preferred and novel successors in turn",
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
