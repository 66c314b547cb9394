"""Enforced hill climbing with h_FF (Hoffmann and Nebel's FF planner).

From the current state, a breadth-first search looks for any state with a
strictly lower h_FF, and the climb jumps there. As in the class project we
started from, children with equal heuristic values are taken first-in
first-out: among the improving children of an expanded state, the one with the
lowest h wins, and among those the one generated first. This avoids
flip-flopping between equally good actions.

EHC is incomplete: a breadth-first search that exhausts the states reachable
from a plateau without improving means a dead end, and the search says so
instead of looping.
"""

from __future__ import annotations

from collections import deque

from kitchen_tamp.planning.heuristics import INFINITY, HeuristicName, make_heuristic
from kitchen_tamp.planning.search.breadth_first import unsolvable_message
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, extract_plan
from kitchen_tamp.planning.task import GroundAction, State, Task


def enforced_hill_climbing(
    task: Task, *, heuristic: HeuristicName = "hff", time_budget: float | None = None,
    max_expansions: int | None = None,
) -> SearchResult:
    budget = SearchBudget(time_budget, max_expansions)
    h = make_heuristic(task, heuristic)
    state = task.initial_state
    h_state = h(state)
    evaluated, expanded, generated = 1, 0, 1
    plan: list[GroundAction] = []
    if h_state == INFINITY:
        message = (unsolvable_message(task, 1) if task.trivially_unsolvable
                   else "unsolvable: the goal is unreachable even ignoring delete effects")
        return SearchResult("ehc", "unsolvable", None, 0, 1, 1, budget.elapsed(), message)
    while not task.is_goal(state):
        parents: dict[State, tuple[State, GroundAction] | None] = {state: None}
        frontier = deque([state])
        improved: tuple[State, float] | None = None
        while frontier and improved is None:
            if budget.exhausted(expanded):
                return SearchResult("ehc", "budget", None, expanded, generated, evaluated,
                                    budget.elapsed(), budget.describe())
            node = frontier.popleft()
            expanded += 1
            best: tuple[float, State] | None = None
            for action, child in task.successors(node):
                if child in parents:
                    continue
                parents[child] = (node, action)
                generated += 1
                if task.is_goal(child):
                    best = (-1.0, child)
                    break
                h_child = h(child)
                evaluated += 1
                if h_child == INFINITY:
                    continue
                if h_child < h_state and (best is None or h_child < best[0]):
                    best = (h_child, child)  # strict '<': the first generated wins ties
                frontier.append(child)
            if best is not None:
                improved = (best[1], max(best[0], 0.0))
        if improved is None:
            return SearchResult(
                "ehc", "failed", None, expanded, generated, evaluated, budget.elapsed(),
                f"enforced hill climbing hit a dead end after {len(plan)} action(s): no state "
                f"reachable from there improves on h_FF = {h_state:g} (try bfs, gbfs or astar)")
        state, h_state = improved
        plan.extend(extract_plan(parents, state))
    return SearchResult("ehc", "solved", tuple(plan), expanded, generated, evaluated,
                        budget.elapsed())
