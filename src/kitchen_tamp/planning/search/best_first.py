"""Best-first searches over a heuristic: greedy best-first (GBFS) and A*.

Both keep a priority queue; they differ in the priority (h, or g + h) and in
whether a state reached again by a cheaper path is reopened. Ties are broken
first-in first-out, so runs are deterministic.

GBFS with h_FF also uses the helpful actions (preferred operators) of each
state by default: ``alternating_greedy`` keeps the children they reach in a
second queue, and the children that make an atom true for the first time in a
third, which take turns with the queue of all children, boosted while the
search makes progress, as Fast Downward does (lazy by default, eager with
``lazy=False``). ``preferred_operators=False`` is the plain search here.
"""

from __future__ import annotations

import heapq
import itertools

from kitchen_tamp.planning.heuristics import INFINITY, Heuristic, HeuristicName, make_heuristic
from kitchen_tamp.planning.search.alternating_greedy import alternating_greedy_search
from kitchen_tamp.planning.search.breadth_first import dead_root_result, unsolvable_message
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_to
from kitchen_tamp.planning.task import State, Task

Entry = tuple[float, float, int, int, State]
"""A queue entry: (priority, h, insertion order, g, state); the order makes ties first-in first-out."""


def greedy_best_first_search(
    task: Task, *, heuristic: HeuristicName = "hff", preferred_operators: bool = True,
    lazy: bool = True, time_budget: float | None = None, max_expansions: int | None = None,
) -> SearchResult:
    """Expand the state with the lowest h first; fast, plans not necessarily shortest.

    ``preferred_operators`` (h_FF only): a queue of the children reached by
    helpful actions and one of the novel children take turns with the queue of
    all children, boosted on progress; ``lazy``: children are evaluated when
    taken out of a queue, not when generated (see ``alternating_greedy``).
    """
    if heuristic == "hff" and preferred_operators:
        return alternating_greedy_search(task, SearchBudget(time_budget, max_expansions), lazy=lazy)
    return _best_first(task, "gbfs", make_heuristic(task, heuristic), greedy=True,
                       time_budget=time_budget, max_expansions=max_expansions)


def astar_search(
    task: Task, *, heuristic: HeuristicName = "lmcut", time_budget: float | None = None,
    max_expansions: int | None = None,
) -> SearchResult:
    """A*: optimal plans with an admissible heuristic (the default, LM-cut, and h_max are)."""
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
    if h_root == INFINITY:
        return dead_root_result(task, planner, budget)
    # From here on no goal atom is unreachable, so the goal test is two mask tests.
    goal, goal_neg = task.goal, task.goal_neg
    parents: dict[State, State | None] = {root: None}
    best_g: dict[State, int] = {root: 0}
    h_of: dict[State, float] = {}  # A* only: h of states that may be reopened
    order = itertools.count()
    heap: list[Entry] = [(h_root, h_root, next(order), 0, root)]
    heappop, heappush = heapq.heappop, heapq.heappush
    successors = task.successor_indices
    expanded = 0
    check_at = 0.0
    while heap:
        if expanded >= check_at:
            if budget.exhausted(expanded):
                return SearchResult(planner, "budget", None, expanded, len(parents), evaluated,
                                    budget.elapsed(), budget.describe())
            check_at = budget.next_check(expanded)
        _, _, _, g, state = heappop(heap)
        if g > best_g[state]:
            continue  # a cheaper path to this state was found after this entry was queued
        if state & goal == goal and not state & goal_neg:
            return SearchResult(planner, "solved", plan_to(task, parents, state), expanded,
                                len(parents), evaluated, budget.elapsed())
        expanded += 1
        child_g = g + 1
        for child, _ in successors(state):
            known = best_g.get(child)
            if known is not None:
                if greedy or known <= child_g:
                    continue
                h_child = h_of[child]  # reopened (A*): its h was computed before
            else:
                h_child = h(child)
                evaluated += 1
                if not greedy:
                    h_of[child] = h_child
            best_g[child] = child_g
            parents[child] = state
            if h_child == INFINITY:
                continue  # dead end under the relaxation: no plan passes through it
            priority = h_child if greedy else child_g + h_child
            heappush(heap, (priority, h_child, next(order), child_g, child))
    return SearchResult(planner, "unsolvable", None, expanded, len(parents), evaluated,
                        budget.elapsed(), unsolvable_message(task, len(parents)))
