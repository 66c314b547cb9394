"""PDDL to grounded STRIPS, searches and plan validation. Knows nothing of robots.

Typical use::

    task = load_task("pddl/problem_hard.pddl")
    result = plan(task, "astar")
    assert validate_plan(task, result.plan).valid

Importing the package loads neither Lark nor the ``pddl`` package: they are
imported when a file needs them (``reading``), so a run served from the task
cache, or one whose files the fast reader takes, never loads them.
"""

from __future__ import annotations

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
from kitchen_tamp.planning.validation import PlanValidation, parse_plan_text, plan_text, validate_plan

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
