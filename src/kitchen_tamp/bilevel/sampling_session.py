"""The bookkeeping every planner shares: draw one sample, check it, record it, watch the budgets."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import AbstractPlan, AbstractTransition
from kitchen_tamp.bilevel.planning_graph import ActionEdge, FailedSample, PlanningGraph
from kitchen_tamp.bilevel.problem import BilevelProblem, SamplingFailure
from kitchen_tamp.bilevel.results import Outcome, RefinedPlan, RefinedStep, SampleEvent

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")

SampleCallback = Callable[[SampleEvent[S, A]], None]
"""Called after every sample, e.g. to print a progress line."""


@dataclass(frozen=True)
class Budget:
    """Limits on a whole planner run; ``None`` means no limit."""

    max_samples: int | None = None
    time_budget_s: float | None = None

    def __post_init__(self) -> None:
        if self.max_samples is not None and self.max_samples < 0:
            raise ValueError(f"max_samples must be >= 0, got {self.max_samples}")
        if self.time_budget_s is not None and self.time_budget_s < 0:
            raise ValueError(f"time_budget_s must be >= 0, got {self.time_budget_s}")


class SamplingSession(Generic[X, U, S, A]):
    """One planner run's graph, counters, clock and RNG.

    The graph starts with the problem's initial state as node :attr:`root`.
    """

    def __init__(
        self,
        problem: BilevelProblem[X, U, S, A],
        rng: np.random.Generator,
        budget: Budget,
        on_sample: SampleCallback[S, A] | None = None,
    ) -> None:
        self.problem = problem
        self.rng = rng
        self.budget = budget
        self.on_sample = on_sample
        self.graph: PlanningGraph[X, U, S, A] = PlanningGraph()
        self.samples = 0
        self.failures = 0
        self._start = time.perf_counter()
        initial = problem.initial_state
        self.root = self.graph.add_state(initial, problem.abstraction.abstract_state(initial), sample=0)

    def elapsed(self) -> float:
        return time.perf_counter() - self._start

    def budget_spent(self) -> Outcome | None:
        """Which run budget is spent, if any: no further sample may be drawn."""
        if self.budget.max_samples is not None and self.samples >= self.budget.max_samples:
            return Outcome.SAMPLE_BUDGET
        if self.budget.time_budget_s is not None and self.elapsed() >= self.budget.time_budget_s:
            return Outcome.TIME_BUDGET
        return None

    def draw(
        self,
        source: int,
        transition: AbstractTransition[S, A],
        plan_index: int | None = None,
        step_index: int | None = None,
    ) -> int | None:
        """Sample ``transition`` from state node ``source``: the new state node, or ``None`` on failure.

        A sample fails when the sampler raises :class:`SamplingFailure` or when its
        trajectory ends in another abstract state than ``transition.target``.
        """
        self.samples += 1
        number = self.samples
        edge = self.graph.abstract_edge(transition, number)
        edge.samples += 1
        sampler = self.problem.sampler_for(transition.action)
        abstraction = self.problem.abstraction
        target: int | None = None
        failure: SamplingFailure | None = None
        try:
            trajectory = sampler(self.graph.state(source), transition, self.rng)
            reached = abstraction.abstract_state(trajectory.final_state)
            if reached != transition.target:
                raise SamplingFailure(f"trajectory ends in abstract state {abstraction.describe(reached)}, "
                                      f"not {abstraction.describe(transition.target)}")
        except SamplingFailure as error:
            failure = error
        if failure is None:
            target = self.graph.add_state(trajectory.final_state, transition.target, number)
            self.graph.add_action_edge(ActionEdge(source, target, transition, trajectory, number))
        else:
            self.failures += 1
            edge.failures += 1
            self.graph.add_failed_sample(FailedSample(source, transition, failure, number))
        if self.on_sample is not None:
            self.on_sample(SampleEvent(
                sample=number,
                transition=transition,
                source_node=source,
                target_node=target,
                failure=None if failure is None else str(failure),
                plan_index=plan_index,
                step_index=step_index,
                seconds=self.elapsed(),
            ))
        return target

    def refined_plan(self, node: int) -> RefinedPlan[X, U, S, A]:
        """The plan that the action edges from the root to state node ``node`` make."""
        edges = self.graph.path_to(node)
        abstract_plan = AbstractPlan(
            (self.graph.abstract_state_of(self.root), *(edge.transition.target for edge in edges)),
            tuple(edge.transition.action for edge in edges),
        )
        steps = tuple(RefinedStep(i, edge.transition, edge.trajectory) for i, edge in enumerate(edges))
        return RefinedPlan(abstract_plan, self.problem.initial_state, steps)
