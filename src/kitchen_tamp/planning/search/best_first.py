"""Best-first searches over a heuristic: greedy best-first (GBFS) and A*.

Both keep a priority queue; they differ in the priority (h, or g + h) and in
whether a state reached again by a cheaper path is reopened. Ties are broken
first-in first-out, so runs are deterministic.

GBFS with h_FF also uses the helpful actions (preferred operators) of each
state, as enforced hill climbing does: only the children reached by a helpful
action of their parent are evaluated and queued; the others are set aside, and
when the queue runs dry they are all evaluated and queued, and the search goes
on. So the search stays complete, but evaluates (the costly part) about a
quarter of the states an eager search over every child evaluates, with the
same expansions on blocks world and gripper. Fast Downward instead queues the
helpful children in a second queue that takes turns with the full one, which
guards better against helpful actions that mislead for a long time, but
evaluates every child.
"""

from __future__ import annotations

import heapq
import itertools

from kitchen_tamp.planning.heuristics import (
    INFINITY,
    Heuristic,
    HeuristicName,
    RelaxedExploration,
    make_heuristic,
)
from kitchen_tamp.planning.search.breadth_first import unsolvable_message
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_to
from kitchen_tamp.planning.task import State, Task

Entry = tuple[float, float, int, int, State]
"""A queue entry: (priority, h, insertion order, g, state); the order makes ties first-in first-out."""


def greedy_best_first_search(
    task: Task, *, heuristic: HeuristicName = "hff", preferred_operators: bool = True,
    time_budget: float | None = None, max_expansions: int | None = None,
) -> SearchResult:
    """Expand the state with the lowest h first; fast, plans not necessarily shortest.

    ``preferred_operators`` (h_FF only): children reached by helpful actions first, the others
    only when those run out.
    """
    if heuristic == "hff" and preferred_operators:
        return _preferred_greedy(task, RelaxedExploration(task), SearchBudget(time_budget, max_expansions))
    return _best_first(task, "gbfs", make_heuristic(task, heuristic), greedy=True,
                       time_budget=time_budget, max_expansions=max_expansions)


def astar_search(
    task: Task, *, heuristic: HeuristicName = "hmax", time_budget: float | None = None,
    max_expansions: int | None = None,
) -> SearchResult:
    """A*: optimal plans with an admissible heuristic (the default, h_max, is)."""
    return _best_first(task, "astar", make_heuristic(task, heuristic), greedy=False,
                       time_budget=time_budget, max_expansions=max_expansions)


def _dead_root(task: Task, planner: str, budget: SearchBudget) -> SearchResult:
    return SearchResult(planner, "unsolvable", None, 0, 1, 1, budget.elapsed(),
                        unsolvable_message(task, 1) if task.trivially_unsolvable
                        else "unsolvable: the goal is unreachable even ignoring delete effects")


def _best_first(
    task: Task, planner: str, h: Heuristic, *, greedy: bool, time_budget: float | None,
    max_expansions: int | None,
) -> SearchResult:
    budget = SearchBudget(time_budget, max_expansions)
    root = task.initial_state
    h_root = h(root)
    evaluated = 1
    if h_root == INFINITY:
        return _dead_root(task, planner, budget)
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


def _preferred_greedy(task: Task, exploration: RelaxedExploration, budget: SearchBudget) -> SearchResult:
    """GBFS with h_FF that queues the helpful children and sets the others aside until the queue is empty."""
    root = task.initial_state
    h_root, helpful_root = exploration.h_ff_helpful(root)
    if h_root == INFINITY:
        return _dead_root(task, "gbfs", budget)
    goal, goal_neg = task.goal, task.goal_neg
    parents: dict[State, State | None] = {root: None}
    helpful: dict[State, int] = {root: helpful_root}
    order = itertools.count()
    heap: list[tuple[float, int, State]] = [(h_root, next(order), root)]
    set_aside: list[tuple[State, State]] = []  # (parent, child) reached by an action that is not helpful
    heappop, heappush = heapq.heappop, heapq.heappush
    evaluate, successors = exploration.h_ff_helpful, task.successor_indices
    expanded, evaluated = 0, 1

    def enqueue(parent: State, child: State) -> None:
        nonlocal evaluated
        parents[child] = parent
        h_child, helpful_child = evaluate(child)
        evaluated += 1
        if h_child != INFINITY:  # else a dead end under the relaxation: no plan passes through it
            helpful[child] = helpful_child
            heappush(heap, (h_child, next(order), child))

    check_at = 0.0
    while heap or set_aside:
        if not heap:
            for parent, child in set_aside:
                if child not in parents:
                    enqueue(parent, child)
            set_aside = []
            continue
        if expanded >= check_at:
            if budget.exhausted(expanded):
                return SearchResult("gbfs", "budget", None, expanded, len(parents), evaluated,
                                    budget.elapsed(), budget.describe())
            check_at = budget.next_check(expanded)
        _, _, state = heappop(heap)
        if state & goal == goal and not state & goal_neg:
            return SearchResult("gbfs", "solved", plan_to(task, parents, state), expanded,
                                len(parents), evaluated, budget.elapsed())
        expanded += 1
        preferred = helpful.pop(state)
        for child, index in successors(state):
            if child in parents:
                continue
            if (preferred >> index) & 1:
                enqueue(state, child)
            else:
                set_aside.append((state, child))
    return SearchResult("gbfs", "unsolvable", None, expanded, len(parents), evaluated,
                        budget.elapsed(), unsolvable_message(task, len(parents)))
