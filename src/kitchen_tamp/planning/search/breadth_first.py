"""Breadth-first search: optimal in plan length, blind."""

from __future__ import annotations

from collections import deque

from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, extract_plan
from kitchen_tamp.planning.task import GroundAction, State, Task


def breadth_first_search(
    task: Task, *, time_budget: float | None = None, max_expansions: int | None = None
) -> SearchResult:
    """Shortest plan by breadth-first search with duplicate detection.

    The goal test happens when a state is generated, which is still optimal for
    unit costs and saves expanding the last layer.
    """
    budget = SearchBudget(time_budget, max_expansions)
    root = task.initial_state
    parents: dict[State, tuple[State, GroundAction] | None] = {root: None}
    if task.is_goal(root):
        return SearchResult("bfs", "solved", (), 0, 1, 0, budget.elapsed())
    if task.trivially_unsolvable:
        return _unsolvable(task, 0, 1, budget)
    frontier = deque([root])
    expanded = 0
    is_goal = task.is_goal
    while frontier:
        if budget.exhausted(expanded):
            return SearchResult("bfs", "budget", None, expanded, len(parents), 0, budget.elapsed(),
                                budget.describe())
        state = frontier.popleft()
        expanded += 1
        for action, child in task.successors(state):
            if child in parents:
                continue
            parents[child] = (state, action)
            if is_goal(child):
                plan = extract_plan(parents, child)
                return SearchResult("bfs", "solved", plan, expanded, len(parents), 0, budget.elapsed())
            frontier.append(child)
    return _unsolvable(task, expanded, len(parents), budget)


def _unsolvable(task: Task, expanded: int, generated: int, budget: SearchBudget) -> SearchResult:
    return SearchResult("bfs", "unsolvable", None, expanded, generated, 0, budget.elapsed(),
                        unsolvable_message(task, generated))


def unsolvable_message(task: Task, reachable_states: int) -> str:
    """Why a complete search found no plan, in one line."""
    if task.unreachable_goal_atoms:
        names = " ".join(sorted("(" + " ".join(a) + ")" for a in task.unreachable_goal_atoms))
        return f"unsolvable: goal atom(s) {names} can never become true"
    return f"unsolvable: none of the {reachable_states} reachable states satisfies the goal"

