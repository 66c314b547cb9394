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
import time
from typing import Generic, TypeVar

from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.landmark_count import Evaluation, LandmarkEvaluator
from kitchen_tamp.planning.search import greedy_kernel_loading as loading
from kitchen_tamp.planning.search.breadth_first import dead_root_result, unsolvable_message
from kitchen_tamp.planning.search.partners import turns_after_work
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_to
from kitchen_tamp.planning.task import State, Task

DEFAULT_BOOST = 1000
"""Turns the preferred and novel queues each get on each improvement of a best h (Fast Downward: 1000)."""

Item = TypeVar("Item")


class AlternatingQueues(Generic[Item]):
    """Per heuristic a queue of all entries and one of the preferred ones, and one of novel ones, in turns.

    The queues are, in the order that wins ties between turns: for each
    heuristic ``k``, all entries and the preferred entries ordered by the
    ``k``-th h value; then the novel entries ordered by the first. Each queue
    has a priority: the number of times it was taken from, minus its boosts;
    ``pop`` takes from the non-empty queue with the lowest priority. ``boost``
    gives the preferred and novel queues ``boost`` turns each. An item in
    several queues comes out once from each: callers skip what they have
    already handled.
    """

    def __init__(self, boost: int, heuristics: int = 1) -> None:
        self.heuristics = heuristics
        count = 2 * heuristics + 1
        self.queues: tuple[list[tuple[float, int, Item]], ...] = tuple([] for _ in range(count))
        self.priorities = [0] * count
        self.boosted = [*range(1, 2 * heuristics, 2), 2 * heuristics]
        self.boost_amount = boost
        self.order = itertools.count()

    def __bool__(self) -> bool:
        return any(self.queues)

    def push(self, h: tuple[float, ...], item: Item, preferred: bool, novel: bool = False) -> None:
        order = next(self.order)
        queues = self.queues
        for k in range(self.heuristics):
            entry = (h[k], order, item)
            heapq.heappush(queues[2 * k], entry)
            if preferred:
                heapq.heappush(queues[2 * k + 1], entry)
        if novel:
            heapq.heappush(queues[-1], (h[0], order, item))

    def boost(self) -> None:
        for side in self.boosted:
            self.priorities[side] -= self.boost_amount

    def pop(self) -> Item:
        priorities, side = self.priorities, -1
        for index, queue in enumerate(self.queues):
            if queue and (side < 0 or priorities[index] < priorities[side]):
                side = index
        priorities[side] += 1
        return heapq.heappop(self.queues[side])[2]


class Novelty:
    """Which states make some atom true for the first time in this search (novelty 1)."""

    def __init__(self, enabled: bool) -> None:
        self.enabled = enabled
        self.seen = 0 if enabled else -1  # disabled: every atom counts as seen

    def is_novel(self, state: State) -> bool:
        """Whether ``state`` holds an atom no earlier state given here held; it then counts as seen."""
        if state & ~self.seen:
            self.seen |= state
            return True
        return False


class _Progress:
    """The best value of each heuristic so far; an improvement of any boosts the queues."""

    def __init__(self, first: tuple[float, ...]) -> None:
        self.best = list(first)

    def improves(self, values: tuple[float, ...]) -> bool:
        improved = False
        for k, value in enumerate(values):
            if value < self.best[k]:
                self.best[k] = value
                improved = True
        return improved


def alternating_greedy_search(task: Task, budget: SearchBudget, *, lazy: bool = True,
                              boost: int = DEFAULT_BOOST, novelty: bool = True,
                              landmarks: bool = True, landmark_preferred: bool = True) -> SearchResult:
    """GBFS with h_FF (and the landmark count), taking turns between all, preferred and novel states.

    ``landmarks=False`` drops the landmark count's queues (h_FF alone, as Fast
    Downward's ``lazy_greedy`` with preferred operators); ``novelty=False`` drops
    the novel queue. The preferred operators are h_FF's helpful actions and the
    landmark count's (LAMA 2008's); ``landmark_preferred=False`` keeps h_FF's
    only, as today's lama-first does (its landmark heuristic has ``pref=false``),
    which expands several times more states on woodworking and depot here.
    A lazy search with the landmark count that goes on long in C is joined by
    other searches taking turns (``partners``).
    """
    evaluator = LandmarkEvaluator(RelaxedExploration(task, "hadd"), landmarks, landmark_preferred)
    root = evaluator.root()
    if root.h_ff == INFINITY:
        return dead_root_result(task, "gbfs", budget)
    novel = Novelty(novelty)
    novel.is_novel(task.initial_state)
    heuristics = 2 if evaluator.count else 1
    if lazy:
        return _lazy(task, evaluator, novel, budget, AlternatingQueues(boost, heuristics))
    return _eager(task, evaluator, novel, budget, AlternatingQueues(boost, heuristics))


def _values(evaluation: Evaluation, heuristics: int) -> tuple[float, ...]:
    return (evaluation.h_ff, evaluation.h_landmarks) if heuristics == 2 else (evaluation.h_ff,)


def _eager(task: Task, evaluator: LandmarkEvaluator, novel: Novelty, budget: SearchBudget,
           queues: AlternatingQueues[State]) -> SearchResult:
    root = task.initial_state
    goal, goal_neg = task.goal, task.goal_neg
    successors, heuristics = task.successor_indices, queues.heuristics
    parents: dict[State, State | None] = {root: None}
    known: dict[State, Evaluation] = {root: evaluator.root()}  # of the states queued and not yet expanded
    queues.push(_values(known[root], heuristics), root, preferred=False)
    progress = _Progress(_values(known[root], heuristics))
    expanded, evaluated, check_at = 0, 1, 0.0
    while queues:
        if expanded >= check_at:
            if budget.exhausted(expanded):
                return SearchResult("gbfs", "budget", None, expanded, len(parents), evaluated,
                                    budget.elapsed(), budget.describe())
            check_at = budget.next_check(expanded)
        state = queues.pop()
        evaluation = known.pop(state, None)
        if evaluation is None:
            continue  # expanded already, when it came out of another queue
        if state & goal == goal and not state & goal_neg:
            return SearchResult("gbfs", "solved", plan_to(task, parents, state), expanded,
                                len(parents), evaluated, budget.elapsed())
        expanded += 1
        for child, index in successors(state):
            if child in parents:
                continue
            parents[child] = state
            child_evaluation = evaluator.child(child, evaluation.accepted)
            evaluated += 1
            if child_evaluation.h_ff == INFINITY:
                continue  # a dead end under the relaxation: no plan passes through it
            known[child] = child_evaluation
            values = _values(child_evaluation, heuristics)
            queues.push(values, child, bool(evaluation.preferred >> index & 1), novel.is_novel(child))
            if progress.improves(values):
                queues.boost()
    return SearchResult("gbfs", "unsolvable", None, expanded, len(parents), evaluated,
                        budget.elapsed(), unsolvable_message(task, len(parents)))


def _lazy(task: Task, evaluator: LandmarkEvaluator, novel: Novelty, budget: SearchBudget,
          queues: AlternatingQueues[tuple[State | None, State]]) -> SearchResult:
    root = task.initial_state
    goal, goal_neg = task.goal, task.goal_neg
    successors, heuristics = task.successor_indices, queues.heuristics
    closed: dict[State, State | None] = {}  # each evaluated state's parent
    accepted: dict[State, int] = {}  # each expanded state's accepted landmarks
    handover = _Handover(evaluator, novel.enabled, queues.boost_amount, budget)
    if (handed_over := handover.search()) is not None:
        return handed_over
    clock = time.process_time()
    root_evaluation = evaluator.root()
    handover.root_evaluated(root_evaluation.h_ff, time.process_time() - clock)
    if handover.due() and (handed_over := handover.search()) is not None:
        return handed_over
    queues.push(_values(root_evaluation, heuristics), (None, root), preferred=False)
    progress = _Progress(_values(root_evaluation, heuristics))
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
        evaluation = root_evaluation if parent is None else evaluator.child(state, accepted[parent])
        if handover.due() and (handed_over := handover.search()) is not None:
            return handed_over  # the search outgrew Python: again from the root, compiled
        evaluated += 1
        if evaluation.h_ff == INFINITY:
            continue
        if state & goal == goal and not state & goal_neg:
            return SearchResult("gbfs", "solved", plan_to(task, closed, state), expanded, generated,
                                evaluated, budget.elapsed())
        accepted[state] = evaluation.accepted
        values = _values(evaluation, heuristics)
        if progress.improves(values):
            queues.boost()
        expanded += 1
        preferred = evaluation.preferred
        for child, index in successors(state):
            if child not in closed:
                generated += 1
                queues.push(values, (state, child), bool(preferred >> index & 1), novel.is_novel(child))
    return SearchResult("gbfs", "unsolvable", None, expanded, generated, evaluated,
                        budget.elapsed(), unsolvable_message(task, len(closed)))


class _Handover:
    """When and how the lazy search goes over to a compiled search (``native_greedy``, ``compiled_greedy``).

    Once the search has spent ``loading.NATIVE_HANDOVER_AFTER_SECONDS`` of CPU time, or sooner when its
    root says that even its shortest run would take longer in Python (``root_evaluated``) or when its
    evaluator's next state would take it to the JIT exploration (``LandmarkEvaluator.compiles_next``), the
    search in C is looked for (``native_greedy``: no numpy, no numba). Without it, the search goes over to
    numba's JIT kernel once the evaluator has switched to the JIT exploration (``COMPILED_AFTER_WORK``),
    which has imported numba already. In C, a search with the landmark count is joined by ``PARTNERS``
    after ``PARTNERS_AFTER_WORK`` (``partners.py``)."""

    def __init__(self, evaluator: LandmarkEvaluator, novelty: bool, boost: int, budget: SearchBudget) -> None:
        self.evaluator, self.novelty, self.boost, self.budget = evaluator, novelty, boost, budget
        self.due_at = time.process_time() + loading.NATIVE_HANDOVER_AFTER_SECONDS
        self.native_looked_for = False

    def root_evaluated(self, h_ff: float, seconds: float) -> None:
        """The root's evaluation took ``seconds``: a search of at least ``h_ff`` such evaluations that would
        take longer than handing over hands over now."""
        if h_ff * seconds > loading.NATIVE_HANDOVER_AFTER_SECONDS:
            self.due_at = 0.0

    def due(self) -> bool:
        if self.evaluator.compiled is not None or self.evaluator.compiles_next():
            return True
        return not self.native_looked_for and time.process_time() > self.due_at

    def search(self) -> SearchResult | None:
        """The compiled search's result, or None: no compiled search yet (go on in Python)."""
        if not self.native_looked_for and self.due():
            self.native_looked_for = True
            library = loading.native_library()
            if library is not None:
                from kitchen_tamp.planning.search.native_greedy import native_lazy_search

                evaluator = self.evaluator
                turns = None if evaluator.count is None else turns_after_work(evaluator.work_per_evaluation)
                return native_lazy_search(evaluator, self.novelty, self.boost, self.budget, library, turns)
        if self.evaluator.compiled is None:
            return None
        from kitchen_tamp.planning.search.compiled_greedy import compiled_lazy_search  # numpy and numba

        kernel = loading.jit_kernel()
        return compiled_lazy_search(self.evaluator, self.novelty, self.boost, self.budget, kernel)
