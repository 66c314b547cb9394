"""Greedy best-first search with h_FF over alternating queues, as Fast Downward and LAMA do, plus novelty.

Helpful actions (preferred operators) are a strong guide but not a safe one: in
domains full of dead ends and plateaus the states they lead to can go on
looking promising for a long time. A search that only looks elsewhere once
they run out (our earlier GBFS) or never does (pyperplan's pruning) is then
lost. Here every child goes into a queue of *all* states, the children reached
by a helpful action also into a *preferred* queue, and the children that make
some atom true for the first time in the whole search into a *novel* queue
(novelty 1, as in Lipovetzky and Geffner's width-based search); each queue is
ordered by h, ties first-in first-out, and the search takes turns between them.
Each time a state with a new lowest h is found, the preferred and novel queues
are *boosted*: they get ``boost`` turns each (Fast Downward's ``boost=1000``),
so the search rushes down helpful actions while they make progress and falls
back to taking turns when they stop.

The novel queue is what gets out of a dead-end region that the relaxation
cannot see, which is how mystery-10 defeats boosted helpful actions (Fast
Downward's eager search among them): a plateau of thousands of states that
differ only in moves that leave h unchanged keeps the other two queues busy,
while the novel queue holds at most one state per atom of the task, so it soon
reaches the alternatives that the other queues left behind. Every non-dead
child sits in the all-states queue, so the search is complete.

``lazy=True`` (the default) defers evaluation as Fast Downward's lazy search
and LAMA do: a child is queued with its parent's h and evaluated only when
taken out of a queue, so children never chosen are never evaluated; eager
search evaluates every child when it is generated. The relaxed plan behind h_FF
and the helpful actions comes from h_add's best supporters, as in Fast Downward
(``RelaxedExploration(task, "hadd")``): on mystery-10 FF's planning graph prefers
the shallow route of the first layer holding the goal, which is the dead end.
"""

from __future__ import annotations

import heapq
import itertools
from typing import Generic, TypeVar

from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration, RelaxedPlanSupporters
from kitchen_tamp.planning.search.breadth_first import dead_root_result, unsolvable_message
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_to
from kitchen_tamp.planning.task import State, Task

DEFAULT_BOOST = 1000
"""Turns the preferred and novel queues each get on each improvement of the best h (Fast Downward: 1000)."""

ALL, PREFERRED, NOVEL = 0, 1, 2
"""The queues, in the order that wins ties between turns."""

Item = TypeVar("Item")


class AlternatingQueues(Generic[Item]):
    """A queue of all entries, one of the preferred and one of the novel ones, taken in turns, with boosting.

    Each queue has a priority: the number of times it was taken from, minus its
    boosts; ``pop`` takes from the non-empty queue with the lowest priority
    (ties in the order all, preferred, novel). An item in several queues comes
    out once from each: callers skip what they have already handled.
    """

    def __init__(self, boost: int) -> None:
        self.queues: tuple[list[tuple[float, int, Item]], ...] = ([], [], [])
        self.priorities = [0, 0, 0]
        self.boost_amount = boost
        self.order = itertools.count()

    def __bool__(self) -> bool:
        return any(self.queues)

    def push(self, h: float, item: Item, preferred: bool, novel: bool = False) -> None:
        entry = (h, next(self.order), item)
        heapq.heappush(self.queues[ALL], entry)
        if preferred:
            heapq.heappush(self.queues[PREFERRED], entry)
        if novel:
            heapq.heappush(self.queues[NOVEL], entry)

    def boost(self) -> None:
        self.priorities[PREFERRED] -= self.boost_amount
        self.priorities[NOVEL] -= self.boost_amount

    def pop(self) -> Item:
        side = min((i for i in (ALL, PREFERRED, NOVEL) if self.queues[i]),
                   key=self.priorities.__getitem__)
        self.priorities[side] += 1
        return heapq.heappop(self.queues[side])[2]


class Novelty:
    """Which states make some atom true for the first time in this search (novelty 1)."""

    def __init__(self, enabled: bool) -> None:
        self.seen = 0 if enabled else -1  # disabled: every atom counts as seen

    def is_novel(self, state: State) -> bool:
        """Whether ``state`` holds an atom no earlier state given here held; it then counts as seen."""
        if state & ~self.seen:
            self.seen |= state
            return True
        return False


def alternating_greedy_search(task: Task, budget: SearchBudget, *, lazy: bool = True,
                              boost: int = DEFAULT_BOOST, novelty: bool = True,
                              supporters: RelaxedPlanSupporters = "hadd") -> SearchResult:
    """GBFS with h_FF, taking turns between all states, those reached by helpful actions and novel ones.

    ``novelty=False`` drops the novel queue (two queues, as Fast Downward's
    ``eager_greedy``/``lazy_greedy`` with preferred operators); ``supporters``
    picks where the relaxed plan's achievers come from (see ``heuristics``).
    """
    exploration = RelaxedExploration(task, supporters)
    h_root, helpful_root = exploration.h_ff_helpful(task.initial_state)
    if h_root == INFINITY:
        return dead_root_result(task, "gbfs", budget)
    novel = Novelty(novelty)
    novel.is_novel(task.initial_state)
    search = _lazy if lazy else _eager
    return search(task, exploration, novel, budget, boost, h_root, helpful_root)


def _eager(task: Task, exploration: RelaxedExploration, novel: Novelty, budget: SearchBudget,
           boost: int, h_root: float, helpful_root: int) -> SearchResult:
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
            continue  # expanded already, when it came out of another queue
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
            queues.push(h_child, child, bool((preferred_actions >> index) & 1), novel.is_novel(child))
            if h_child < best_h:
                best_h = h_child
                queues.boost()
    return SearchResult("gbfs", "unsolvable", None, expanded, len(parents), evaluated,
                        budget.elapsed(), unsolvable_message(task, len(parents)))


def _lazy(task: Task, exploration: RelaxedExploration, novel: Novelty, budget: SearchBudget,
          boost: int, h_root: float, helpful_root: int) -> SearchResult:
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
                queues.push(h_state, (state, child), bool((preferred_actions >> index) & 1),
                            novel.is_novel(child))
    return SearchResult("gbfs", "unsolvable", None, expanded, generated, evaluated,
                        budget.elapsed(), unsolvable_message(task, len(closed)))
