"""Greedy best-first search with h_FF over two alternating queues, as Fast Downward does.

Helpful actions (preferred operators) are a strong guide but not a safe one: in
domains full of dead ends and plateaus the states they lead to can go on
looking promising for a long time. A search that only looks elsewhere once
they run out (our earlier GBFS) or never does (pyperplan's pruning) is then
lost. Here every child goes into a queue of *all* states and the children
reached by a helpful action also into a *preferred* queue, both ordered by h
(ties first-in first-out); the search takes turns between them. Each time a
state with a new lowest h is found, the preferred queue is *boosted*: it gets
``boost`` turns in a row (Fast Downward's ``boost=1000``), so the search rushes
down helpful actions while they make progress and falls back to taking turns
when they stop. Every non-dead child sits in the all-states queue, so the
search is complete.

``lazy=True`` defers evaluation as Fast Downward's lazy search (and LAMA) does:
a child is queued with its parent's h and evaluated only when taken out of a
queue, so children never chosen are never evaluated; eager search (the
default) evaluates every child when it is generated.
"""

from __future__ import annotations

import heapq
import itertools

from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.search.breadth_first import dead_root_result, unsolvable_message
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_to
from kitchen_tamp.planning.task import State, Task

DEFAULT_BOOST = 1000
"""Turns the preferred queue gets in a row after each improvement of the best h (Fast Downward's default)."""

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from typing import Generic, TypeVar
else:  # what the generic class needs at run time, where its type parameter is never looked at

    class Generic:
        def __class_getitem__(cls, _parameter: object) -> type:
            return cls

    def TypeVar(name: str) -> str:
        return name


Item = TypeVar("Item")


class AlternatingQueues(Generic[Item]):
    """A queue of all entries and a queue of the preferred ones, taken in turns, with boosting.

    Each queue has a priority: the number of times it was taken from, minus its
    boosts; ``pop`` takes from the non-empty queue with the lower priority (the
    all-entries queue on ties). An item in both queues comes out twice: callers
    skip what they have already handled.
    """

    def __init__(self, boost: int) -> None:
        self.queues: tuple[list[tuple[float, int, Item]], list[tuple[float, int, Item]]] = ([], [])
        self.priorities = [0, 0]
        self.boost_amount = boost
        self.order = itertools.count()

    def __bool__(self) -> bool:
        return bool(self.queues[0] or self.queues[1])

    def push(self, h: float, item: Item, preferred: bool) -> None:
        entry = (h, next(self.order), item)
        heapq.heappush(self.queues[0], entry)
        if preferred:
            heapq.heappush(self.queues[1], entry)

    def boost(self) -> None:
        self.priorities[1] -= self.boost_amount

    def pop(self) -> Item:
        everything, preferred = self.queues
        side = 1 if preferred and (not everything or self.priorities[1] < self.priorities[0]) else 0
        self.priorities[side] += 1
        return heapq.heappop(self.queues[side])[2]


def alternating_greedy_search(task: Task, budget: SearchBudget, *, lazy: bool = False,
                              boost: int = DEFAULT_BOOST) -> SearchResult:
    """GBFS with h_FF, taking turns between all states and those reached by helpful actions."""
    exploration = RelaxedExploration(task)
    h_root, helpful_root = exploration.h_ff_helpful(task.initial_state)
    if h_root == INFINITY:
        return dead_root_result(task, "gbfs", budget)
    if lazy:
        return _lazy(task, exploration, budget, boost, h_root, helpful_root)
    return _eager(task, exploration, budget, boost, h_root, helpful_root)


def _eager(task: Task, exploration: RelaxedExploration, budget: SearchBudget, boost: int,
           h_root: float, helpful_root: int) -> SearchResult:
    root = task.initial_state
    goal, goal_neg = task.goal, task.goal_neg
    evaluate, successors = exploration.h_ff_helpful, task.successor_indices
    parents: dict[State, State | None] = {root: None}
    helpful: dict[State, int] = {root: helpful_root}  # of the states queued and not yet expanded
    queues: AlternatingQueues[State] = AlternatingQueues(boost)
    queues.push(h_root, root, preferred=False)
    best_h = h_root
    expanded, evaluated, check_at = 0, 1, 0.0
    while queues:
        if expanded >= check_at:
            if budget.exhausted(expanded):
                return SearchResult("gbfs", "budget", None, expanded, len(parents), evaluated,
                                    budget.elapsed(), budget.describe())
            check_at = budget.next_check(expanded)
        state = queues.pop()
        preferred_actions = helpful.pop(state, None)
        if preferred_actions is None:
            continue  # expanded already, when it came out of the other queue
        if state & goal == goal and not state & goal_neg:
            return SearchResult("gbfs", "solved", plan_to(task, parents, state), expanded,
                                len(parents), evaluated, budget.elapsed())
        expanded += 1
        for child, index in successors(state):
            if child in parents:
                continue
            parents[child] = state
            h_child, helpful_child = evaluate(child)
            evaluated += 1
            if h_child == INFINITY:
                continue  # a dead end under the relaxation: no plan passes through it
            helpful[child] = helpful_child
            queues.push(h_child, child, preferred=bool((preferred_actions >> index) & 1))
            if h_child < best_h:
                best_h = h_child
                queues.boost()
    return SearchResult("gbfs", "unsolvable", None, expanded, len(parents), evaluated,
                        budget.elapsed(), unsolvable_message(task, len(parents)))


def _lazy(task: Task, exploration: RelaxedExploration, budget: SearchBudget, boost: int,
          h_root: float, helpful_root: int) -> SearchResult:
    root = task.initial_state
    goal, goal_neg = task.goal, task.goal_neg
    evaluate, successors = exploration.h_ff_helpful, task.successor_indices
    closed: dict[State, State | None] = {}  # each evaluated state's parent
    queues: AlternatingQueues[tuple[State | None, State]] = AlternatingQueues(boost)
    queues.push(h_root, (None, root), preferred=False)
    best_h = h_root
    expanded, generated, evaluated, check_at = 0, 1, 0, 0.0
    while queues:
        if expanded >= check_at:
            if budget.exhausted(expanded):
                return SearchResult("gbfs", "budget", None, expanded, generated, evaluated,
                                    budget.elapsed(), budget.describe())
            check_at = budget.next_check(expanded)
        parent, state = queues.pop()
        if state in closed:
            continue
        closed[state] = parent
        if parent is None:
            h_state, preferred_actions = h_root, helpful_root
        else:
            h_state, preferred_actions = evaluate(state)
        evaluated += 1
        if h_state == INFINITY:
            continue
        if state & goal == goal and not state & goal_neg:
            return SearchResult("gbfs", "solved", plan_to(task, closed, state), expanded, generated,
                                evaluated, budget.elapsed())
        if h_state < best_h:
            best_h = h_state
            queues.boost()
        expanded += 1
        for child, index in successors(state):
            if child not in closed:
                generated += 1
                queues.push(h_state, (state, child), preferred=bool((preferred_actions >> index) & 1))
    return SearchResult("gbfs", "unsolvable", None, expanded, generated, evaluated,
                        budget.elapsed(), unsolvable_message(task, len(closed)))
