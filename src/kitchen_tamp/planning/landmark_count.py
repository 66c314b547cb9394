"""LAMA's landmark-count heuristic and its preferred operators, beside h_FF from one relaxed exploration.

Richter and Westphal's landmark count is path-dependent: a state carries the
set of landmarks its path has *accepted*. At the start these are the landmarks
that hold; a landmark becomes accepted when it holds in a state reached from a
parent in which every landmark naturally ordered before it was accepted
(``accepted_after``). Then

    h_LM(s) = |landmarks not accepted| + |accepted landmarks needed again|,

where an accepted landmark is needed again when it is false in ``s`` and is a
goal or must hold right before (greedy-necessary ordering) some landmark not
yet accepted. Landmarks come from ``landmarks.landmark_graph``.

Its preferred operators (LAMA's) are the applicable actions that achieve a
landmark to be reached next: one not accepted whose natural predecessors all
are, or one needed again. When no applicable action does, they are the
applicable actions of the relaxed plan (h_add's best supporters) to the
nearest such landmarks, so the search is never without a direction.

``LandmarkEvaluator`` serves a greedy search: one h_add exploration per state
gives h_FF and its helpful actions, and the same costs give the landmark
count's preferred operators.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

from kitchen_tamp.planning.heuristics import INFINITY
from kitchen_tamp.planning.landmarks import landmark_graph
from kitchen_tamp.planning.task import bits

if TYPE_CHECKING:
    from kitchen_tamp.planning.compiled_exploration import CompiledExploration, CompiledLandmarkCount
    from kitchen_tamp.planning.heuristics import RelaxedExploration
    from kitchen_tamp.planning.landmarks import LandmarkGraph
    from kitchen_tamp.planning.task import State


class LandmarkCount:
    """The landmark-count heuristic over one landmark graph (computed for the task's initial state)."""

    def __init__(self, exploration: RelaxedExploration, graph: LandmarkGraph) -> None:
        task = exploration.task
        self.graph = graph
        self.landmarks = graph.landmarks
        self.goal = task.goal
        self.natural = graph.natural
        self.greedy_necessary = graph.greedy_necessary
        self.achievers = graph.achievers
        self.applicability = [(action.pre, action.pre_neg) for action in task.actions]

    def accepted_at_start(self, state: State) -> int:
        """The landmarks accepted at the root: those that hold in it."""
        return self.landmarks & state

    def accepted_after(self, parent_accepted: int, state: State) -> int:
        """The landmarks accepted in ``state`` reached from a parent that had accepted ``parent_accepted``."""
        accepted = parent_accepted
        natural = self.natural
        for atom in bits(state & self.landmarks & ~parent_accepted):
            if not natural[atom] & ~parent_accepted:
                accepted |= 1 << atom
        return accepted

    def value(self, state: State, accepted: int) -> tuple[int, int]:
        """h_LM of ``state`` and the landmarks to reach next (a bitset over atoms)."""
        unaccepted = self.landmarks & ~accepted
        needed = self.goal
        greedy_necessary, natural = self.greedy_necessary, self.natural
        next_up = 0
        for atom in bits(unaccepted):
            needed |= greedy_necessary[atom]
            if not natural[atom] & unaccepted:
                next_up |= 1 << atom
        again = accepted & ~state & needed
        return unaccepted.bit_count() + again.bit_count(), next_up | again

    def achieving_actions(self, state: State, targets: int) -> int:
        """The applicable actions adding one of ``targets``, as a bitset over action indices."""
        preferred = 0
        applicability, achievers = self.applicability, self.achievers
        for atom in bits(targets):
            for action in achievers[atom]:
                pre, pre_neg = applicability[action]
                if state & pre == pre and not state & pre_neg:
                    preferred |= 1 << action
        return preferred


class Evaluation(NamedTuple):
    """What the greedy search knows of a state: h_FF, h_LM, preferred actions, accepted landmarks."""

    h_ff: float
    h_landmarks: float
    preferred: int
    accepted: int


DEAD_END = Evaluation(INFINITY, INFINITY, 0, 0)

COMPILED_AFTER_WORK = 5_000_000
"""Evaluations times ``work_per_evaluation`` after which ``LandmarkEvaluator`` evaluates through the compiled
kernels (``compiled_exploration``): about the Python work that costs as much as loading numba and them."""


class LandmarkEvaluator:
    """h_FF with helpful actions and the landmark count with its preferred operators, from one exploration."""

    def __init__(self, exploration: RelaxedExploration, use_landmarks: bool = True,
                 landmark_preferred: bool = True) -> None:
        self.exploration = exploration
        self.landmark_preferred = landmark_preferred
        task = exploration.task
        graph = landmark_graph(exploration, task.initial_state) if use_landmarks else None
        self.count = None if graph is None else LandmarkCount(exploration, graph)
        self.pre_masks = exploration.pre_masks
        self.evaluations = self.dead_ends = 0
        self.compiled: CompiledExploration | None = None
        self.compiled_count: CompiledLandmarkCount | None = None
        self.compiled_after_work = COMPILED_AFTER_WORK
        # What one evaluation costs in Python grows with the relevant actions' preconditions and effects.
        self.work_per_evaluation = sum(
            len(exploration.preconditions_of[index]) + len(exploration.adds_of[index])
            for _, _, index in exploration.entries)

    def root(self) -> Evaluation:
        state = self.exploration.task.initial_state
        accepted = 0 if self.count is None else self.count.accepted_at_start(state)
        return self.evaluate(state, accepted)

    def child(self, state: State, parent_accepted: int) -> Evaluation:
        """The evaluation of ``state`` reached from a parent that had accepted ``parent_accepted``."""
        accepted = 0 if self.count is None else self.count.accepted_after(parent_accepted, state)
        return self.evaluate(state, accepted)

    def compiles_next(self) -> bool:
        """Whether the next evaluation goes over to the compiled exploration (importing numba)."""
        next_work = (self.evaluations + 1) * self.work_per_evaluation
        return self.compiled is None and next_work > self.compiled_after_work

    def evaluate(self, state: State, accepted: int) -> Evaluation:
        exploration = self.exploration
        if exploration.unsolvable:
            return DEAD_END
        compiles = self.compiles_next()
        self.evaluations += 1
        if compiles:
            from kitchen_tamp.planning.compiled_exploration import (  # numba: large tasks only
                CompiledExploration,
                CompiledLandmarkCount,
            )

            achievers = None if self.count is None else self.count.achievers
            self.compiled = CompiledExploration(exploration, achievers)
            if self.count is not None:
                self.compiled_count = CompiledLandmarkCount(self.count, self.compiled.state_bytes)
        if self.compiled is not None:
            return self._evaluate_compiled(self.compiled, state, accepted)
        if self.dead_ends * 4 > self.evaluations and exploration.atom_layers(state) is None:
            # A quarter of the states so far were dead ends: the bitset reachability test that tells
            # them is several times cheaper than h_add's exploration, which would find the same.
            self.dead_ends += 1
            return DEAD_END
        explored = exploration.additive_costs(state)
        if explored is None:
            self.dead_ends += 1
            return DEAD_END
        cost, supporter = explored
        plan = exploration.supported_plan(cost, supporter, exploration.goal_ids)
        preferred = 0
        pre = self.pre_masks
        for action in plan:
            if pre[action] & state == pre[action]:
                preferred |= 1 << action
        if self.count is None:
            return Evaluation(float(len(plan)), 0.0, preferred, 0)
        h_landmarks, next_up = self.count.value(state, accepted)
        if self.landmark_preferred:
            achieving = self.count.achieving_actions(state, next_up)
            if not achieving and next_up:
                achieving = self._towards_nearest(state, next_up, cost, supporter)
            preferred |= achieving
        return Evaluation(float(len(plan)), float(h_landmarks), preferred, accepted)

    def _evaluate_compiled(self, compiled: CompiledExploration, state: State, accepted: int) -> Evaluation:
        """``evaluate`` with the exploration and the relaxed plan compiled: the same values and operators."""
        state_array = compiled.explore(state)
        if state_array is None:
            self.dead_ends += 1
            return DEAD_END
        length, preferred = compiled.plan_and_helpful(state_array)
        if self.count is None:
            return Evaluation(float(length), 0.0, preferred, 0)
        assert self.compiled_count is not None
        h_landmarks, next_up = self.compiled_count.value(state_array, accepted)
        if self.landmark_preferred:
            achieving = compiled.achieving(state_array, next_up)
            if not achieving and len(next_up):
                achieving = compiled.helpful_towards_nearest(state_array, next_up)
            preferred |= achieving
        return Evaluation(float(length), float(h_landmarks), preferred, accepted)

    def _towards_nearest(self, state: State, targets: int, cost: list[float], supporter: list[int]) -> int:
        """The applicable actions of the relaxed plan to the cheapest of ``targets`` (h_add costs)."""
        reachable = [(cost[atom], atom) for atom in bits(targets) if cost[atom] < INFINITY]
        if not reachable:
            return 0
        nearest = min(reachable)[0]
        plan = self.exploration.supported_plan(cost, supporter, [a for c, a in reachable if c == nearest])
        pre = self.pre_masks
        preferred = 0
        for action in plan:
            if pre[action] & state == pre[action]:
                preferred |= 1 << action
        return preferred
