"""What a bilevel planner returns: the refined plan, per-step records, counts and why it stopped."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Generic, TypeVar

from kitchen_tamp.bilevel.abstraction import AbstractPlan, AbstractTransition
from kitchen_tamp.bilevel.planning_graph import PlanningGraph
from kitchen_tamp.bilevel.trajectory import Trajectory, concatenate

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")


class Outcome(StrEnum):
    """How a planner, or one attempt to refine an abstract plan, ended."""

    SOLVED = "solved"
    STEPS_EXHAUSTED = "every sample of the first step was tried"
    NO_ABSTRACT_PLAN = "no more abstract plans"
    GRAPH_EXHAUSTED = "no abstract state left to expand"
    PLAN_REFUTED = "a fact learned from a failure rules the abstract plan out"
    PLAN_BUDGET = "abstract plan budget spent"
    PLAN_SAMPLE_BUDGET = "sample budget of this abstract plan spent"
    SAMPLE_BUDGET = "sample budget spent"
    TIME_BUDGET = "time budget spent"


@dataclass(frozen=True, eq=False)
class RefinedStep(Generic[X, U, S, A]):
    """Step ``index`` of a refined plan: the abstract transition and the trajectory that realises it."""

    index: int
    transition: AbstractTransition[S, A]
    trajectory: Trajectory[X, U]


@dataclass(frozen=True, eq=False)
class RefinedPlan(Generic[X, U, S, A]):
    """An abstract plan with one trajectory per step, chained from the initial state."""

    abstract_plan: AbstractPlan[S, A]
    initial_state: X
    steps: tuple[RefinedStep[X, U, S, A], ...]

    @property
    def final_state(self) -> X:
        return self.steps[-1].trajectory.final_state if self.steps else self.initial_state

    @property
    def trajectory(self) -> Trajectory[X, U]:
        """All steps' trajectories as one."""
        return concatenate([step.trajectory for step in self.steps], self.initial_state)


@dataclass(frozen=True)
class StepSamplingRecord(Generic[A]):
    """What refining step ``index`` of abstract plan ``plan_index`` took, over all its visits.

    ``backtracks`` counts the times this step was sampled again because a later
    step ran out of samples; ``last_failure`` is the last sampling failure's message.
    """

    plan_index: int
    index: int
    action: A
    samples: int
    failures: int
    backtracks: int
    last_failure: str | None


@dataclass(frozen=True)
class PlanAttempt(Generic[S, A]):
    """One abstract plan and how its refinement went."""

    index: int
    abstract_plan: AbstractPlan[S, A]
    steps: tuple[StepSamplingRecord[A], ...]
    outcome: Outcome
    detail: str

    @property
    def refined(self) -> bool:
        return self.outcome is Outcome.SOLVED


@dataclass(frozen=True)
class PlanningCounts:
    """Totals over a whole planner run. ``abstract_plans`` is 0 for abstract BFS, which has none."""

    samples: int
    failures: int
    backtracks: int
    abstract_plans: int


@dataclass(frozen=True, eq=False)
class SampleEvent(Generic[S, A]):
    """One sample as it happens, for progress lines.

    ``sample`` numbers samples from 1 in the order drawn; ``target_node`` is the
    new state node (``None`` when the sample failed, then ``failure`` says why).
    ``plan_index`` and ``step_index`` are ``None`` for abstract BFS.
    """

    sample: int
    transition: AbstractTransition[S, A]
    source_node: int
    target_node: int | None
    failure: str | None
    plan_index: int | None
    step_index: int | None
    seconds: float

    @property
    def succeeded(self) -> bool:
        return self.target_node is not None


@dataclass(frozen=True, eq=False)
class BilevelResult(Generic[X, U, S, A]):
    """A planner's answer: the plan (``None`` on failure), the graph it built and what it cost.

    ``seconds`` is wall-clock; everything else is the same for the same seed
    unless the time budget cut the run short.
    """

    planner: str
    plan: RefinedPlan[X, U, S, A] | None
    graph: PlanningGraph[X, U, S, A]
    counts: PlanningCounts
    attempts: tuple[PlanAttempt[S, A], ...]
    outcome: Outcome
    detail: str
    seconds: float
    learned: tuple[object, ...] = ()
    """Facts the plan generator learned from failures, in the order learned
    (``kitchen_tamp.bilevel.feedback``)."""

    @property
    def solved(self) -> bool:
        return self.plan is not None
