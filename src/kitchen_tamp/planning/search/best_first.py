"""Best-first searches over a heuristic: greedy best-first (GBFS) and A*.

Both keep one priority queue; they differ in the priority (h, or g + h) and in
whether a state reached again by a cheaper path is reopened. Ties are broken
first-in first-out, so runs are deterministic.
"""

from __future__ import annotations

import heapq
import itertools

from kitchen_tamp.planning.heuristics import INFINITY, Heuristic, HeuristicName, make_heuristic
from kitchen_tamp.planning.search.breadth_first import unsolvable_message
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, extract_plan
from kitchen_tamp.planning.task import GroundAction, State, Task


def greedy_best_first_search(
    task: Task, *, heuristic: HeuristicName = "hff", time_budget: float | None = None,
    max_expansions: int | None = None,
) -> SearchResult:
    """Expand the state with the lowest h first; fast, plans not necessarily shortest."""
    return _best_first(task, "gbfs", make_heuristic(task, heuristic), greedy=True,
                       time_budget=time_budget, max_expansions=max_expansions)


def astar_search(
    task: Task, *, heuristic: HeuristicName = "hmax", time_budget: float | None = None,
    max_expansions: int | None = None,
) -> SearchResult:
    """A*: optimal plans with an admissible heuristic (the default, h_max, is)."""
    return _best_first(task, "astar", make_heuristic(task, heuristic), greedy=False,
                       time_budget=time_budget, max_expansions=max_expansions)


def _best_first(
    task: Task, planner: str, h: Heuristic, *, greedy: bool, time_budget: float | None,
    max_expansions: int | None,
) -> SearchResult:
    budget = SearchBudget(time_budget, max_expansions)
    root = task.initial_state
    h_root = h(root)
    evaluated = 1
    parents: dict[State, tuple[State, GroundAction] | None] = {root: None}
    best_g: dict[State, int] = {root: 0}
    if h_root == INFINITY:
        return SearchResult(planner, "unsolvable", None, 0, 1, evaluated, budget.elapsed(),
                            unsolvable_message(task, 1) if task.trivially_unsolvable
                            else "unsolvable: the goal is unreachable even ignoring delete effects")
    order = itertools.count()
    heap: list[tuple[float, float, int, int, State]] = [(h_root, h_root,
                                                          next(order), 0, root)]
    expanded = 0
    is_goal = task.is_goal
    while heap:
        if budget.exhausted(expanded):
            return SearchResult(planner, "budget", None, expanded, len(parents), evaluated,
                                budget.elapsed(), budget.describe())
        _, _, _, g, state = heapq.heappop(heap)
        if g > best_g[state]:
            continue  # a cheaper path to this state was found after this entry was queued
        if is_goal(state):
            return SearchResult(planner, "solved", extract_plan(parents, state), expanded,
                                len(parents), evaluated, budget.elapsed())
        expanded += 1
        child_g = g + 1
        for action, child in task.successors(state):
            known = best_g.get(child)
            if known is not None and (greedy or known <= child_g):
                continue
            h_child = h(child)
            evaluated += 1
            best_g[child] = child_g
            parents[child] = (state, action)
            if h_child == INFINITY:
                continue  # dead end under the relaxation: no plan passes through it
            priority = h_child if greedy else child_g + h_child
            heapq.heappush(heap, (priority, h_child, next(order), child_g, child))
    return SearchResult(planner, "unsolvable", None, expanded, len(parents), evaluated,
                        budget.elapsed(), unsolvable_message(task, len(parents)))
