"""Breadth-first search: optimal in plan length, blind."""

from __future__ import annotations

from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, StateParents, plan_to
from kitchen_tamp.planning.task import State, Task, atom_text


def breadth_first_search(
    task: Task, *, time_budget: float | None = None, max_expansions: int | None = None
) -> SearchResult:
    """Shortest plan by breadth-first search with duplicate detection.

    The goal test happens when a state is generated, which is still optimal for
    unit costs and saves expanding the last layer. Successors are generated
    inline from the task's successor table (this loop is the whole cost of a
    blind search), in the same order as ``Task.successors``.
    """
    budget = SearchBudget(time_budget, max_expansions)
    root = task.initial_state
    parents: dict[State, State | None] = {root: None}
    if task.is_goal(root):
        return SearchResult("bfs", "solved", (), 0, 1, 0, budget.elapsed())
    if task.trivially_unsolvable:
        return _unsolvable(task, 0, 1, budget)
    key_mask, by_key, unconditional = task.successor_table
    goal, goal_neg = task.goal, task.goal_neg
    layer = [root]
    expanded = 0
    check_at = 0.0
    while layer:
        next_layer: list[State] = []
        for state in layer:
            if expanded >= check_at:
                if budget.exhausted(expanded):
                    return SearchResult("bfs", "budget", None, expanded, len(parents), 0,
                                        budget.elapsed(), budget.describe())
                check_at = budget.next_check(expanded)
            expanded += 1
            keys = state & key_mask
            group = unconditional
            while True:
                for pre, neg, keep, add, _ in group:
                    if state & pre == pre and not state & neg:
                        child = (state & keep) | add
                        if child not in parents:
                            parents[child] = state
                            if child & goal == goal and not child & goal_neg:
                                return _solved(task, parents, child, expanded, budget)
                            next_layer.append(child)
                if not keys:
                    break
                low = keys & -keys
                keys ^= low
                group = by_key[low]
        layer = next_layer
    return _unsolvable(task, expanded, len(parents), budget)


def _solved(task: Task, parents: StateParents, goal_state: State, expanded: int,
            budget: SearchBudget) -> SearchResult:
    return SearchResult("bfs", "solved", plan_to(task, parents, goal_state), expanded, len(parents), 0,
                        budget.elapsed())


def _unsolvable(task: Task, expanded: int, generated: int, budget: SearchBudget) -> SearchResult:
    return SearchResult("bfs", "unsolvable", None, expanded, generated, 0, budget.elapsed(),
                        unsolvable_message(task, generated))


def unsolvable_message(task: Task, reachable_states: int) -> str:
    """Why a complete search found no plan, in one line."""
    if task.unreachable_goal_atoms:
        names = " ".join(sorted(atom_text(a) for a in task.unreachable_goal_atoms))
        return f"unsolvable: goal atom(s) {names} can never become true"
    return f"unsolvable: none of the {reachable_states} reachable states satisfies the goal"


def dead_root_result(task: Task, planner: str, budget: SearchBudget) -> SearchResult:
    """A heuristic search's answer when the initial state is a dead end even under the delete relaxation."""
    message = (unsolvable_message(task, 1) if task.trivially_unsolvable
               else "unsolvable: the goal is unreachable even ignoring delete effects")
    return SearchResult(planner, "unsolvable", None, 0, 1, 1, budget.elapsed(), message)
