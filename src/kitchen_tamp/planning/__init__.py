"""PDDL to grounded STRIPS, searches and plan validation. Knows nothing of robots.

Typical use::

    task = load_task("pddl/problem_hard.pddl")
    result = plan(task, "astar")
    assert validate_plan(task, result.plan).valid

Names are imported on first use (PEP 562), so ``import kitchen_tamp.planning.reading.task_cache``
and the command line pay only for the modules a run needs; in particular a run
served from the task cache never imports Lark or the ``pddl`` package.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from typing import Any

    from kitchen_tamp.planning.errors import PlanningInputError
    from kitchen_tamp.planning.heuristics import RelaxedExploration, make_heuristic
    from kitchen_tamp.planning.loading import load_task
    from kitchen_tamp.planning.search.best_first import astar_search, greedy_best_first_search
    from kitchen_tamp.planning.search.breadth_first import breadth_first_search
    from kitchen_tamp.planning.search.enforced_hill_climbing import enforced_hill_climbing
    from kitchen_tamp.planning.search.plan_iterator import RandomSource, iter_plans, shortest_plans_first
    from kitchen_tamp.planning.search.registry import SEARCH_DESCRIPTIONS, SEARCHES, plan
    from kitchen_tamp.planning.search.result import SearchResult
    from kitchen_tamp.planning.task import Atom, GroundAction, State, Task, atom_text
    from kitchen_tamp.planning.validation import (
        PlanValidation,
        parse_plan_text,
        plan_text,
        validate_plan,
    )

_HOMES: dict[str, str] = {
    "Atom": "kitchen_tamp.planning.task",
    "GroundAction": "kitchen_tamp.planning.task",
    "PlanValidation": "kitchen_tamp.planning.validation",
    "PlanningInputError": "kitchen_tamp.planning.errors",
    "RandomSource": "kitchen_tamp.planning.search.plan_iterator",
    "RelaxedExploration": "kitchen_tamp.planning.heuristics",
    "SEARCHES": "kitchen_tamp.planning.search.registry",
    "SEARCH_DESCRIPTIONS": "kitchen_tamp.planning.search.registry",
    "SearchResult": "kitchen_tamp.planning.search.result",
    "State": "kitchen_tamp.planning.task",
    "Task": "kitchen_tamp.planning.task",
    "astar_search": "kitchen_tamp.planning.search.best_first",
    "atom_text": "kitchen_tamp.planning.task",
    "breadth_first_search": "kitchen_tamp.planning.search.breadth_first",
    "enforced_hill_climbing": "kitchen_tamp.planning.search.enforced_hill_climbing",
    "greedy_best_first_search": "kitchen_tamp.planning.search.best_first",
    "iter_plans": "kitchen_tamp.planning.search.plan_iterator",
    "load_task": "kitchen_tamp.planning.loading",
    "make_heuristic": "kitchen_tamp.planning.heuristics",
    "parse_plan_text": "kitchen_tamp.planning.validation",
    "plan": "kitchen_tamp.planning.search.registry",
    "plan_text": "kitchen_tamp.planning.validation",
    "shortest_plans_first": "kitchen_tamp.planning.search.plan_iterator",
    "validate_plan": "kitchen_tamp.planning.validation",
}
"""Each public name -> the module that defines it."""


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


__all__ = [
    "SEARCHES",
    "SEARCH_DESCRIPTIONS",
    "Atom",
    "GroundAction",
    "PlanValidation",
    "PlanningInputError",
    "RandomSource",
    "RelaxedExploration",
    "SearchResult",
    "State",
    "Task",
    "astar_search",
    "atom_text",
    "breadth_first_search",
    "enforced_hill_climbing",
    "greedy_best_first_search",
    "iter_plans",
    "load_task",
    "make_heuristic",
    "parse_plan_text",
    "plan",
    "plan_text",
    "shortest_plans_first",
    "validate_plan",
]
