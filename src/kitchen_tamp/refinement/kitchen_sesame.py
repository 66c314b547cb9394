"""The kitchen task as SeSamE: abstract plans from our PDDL planner (shortest first), each
action refined by its skill followed by the mode's motion back end, with backtracking.

A low-level state is a ``KitchenState``: a snapshot of the simulated scene (poses,
joints including the gripper and the drawer, attachments) and of the conditions
geometry does not show (``clean``, ``cooked``). The sampler of an action restores
the snapshot, draws one target sample and solves the move (``refine_action`` with
one sample), records the conditions the action's effects set, and returns the
snapshot after the action; Ψ is ``abstract_state`` of the restored scene. A skill
that failed raises ``SkillSamplingFailure``, which carries the ``SkillFailure`` (its
kind, the objects that obstructed it, the region) and, with failure feedback on, the
facts it teaches the abstract search once confirmed (``failure_feedback``): SeSamE's
plan generator learns them, and the next abstract plans move what is in the way first
and leave out what is out of reach.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Final

import numpy as np

from kitchen_tamp.bilevel import (
    AbstractTransition,
    BilevelResult,
    SampleEvent,
    SamplingFailure,
    SesameBudgets,
    Trajectory,
    fact_text,
    relational_problem,
    sesame,
)
from kitchen_tamp.kitchen import KitchenScene, SkillFailure, abstract_state, record_conditions
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Atom, GroundAction, State, Task
from kitchen_tamp.refinement.failure_feedback import FailureFeedback
from kitchen_tamp.refinement.motion_backend import MotionBackend
from kitchen_tamp.refinement.planning_checkers import DEFAULT_COLLISION_MODEL, PlanningCheckers
from kitchen_tamp.refinement.refine_action import ActionSampleRecord, RefinedKitchenPlan, refine_action
from kitchen_tamp.world import SceneState

if TYPE_CHECKING:
    from kitchen_tamp.motion.geometry.drake_service import DrakeService


@dataclass(frozen=True, eq=False)
class KitchenState:
    """A snapshot of the kitchen scene and its conditions: the low-level state x of the bilevel
    problem."""

    scene: SceneState
    conditions: frozenset[Atom] = frozenset()

    @staticmethod
    def of(kitchen: KitchenScene) -> KitchenState:
        """The kitchen as it is now."""
        return KitchenState(kitchen.scene.save_state(), frozenset(kitchen.conditions))

    def restore(self, kitchen: KitchenScene) -> None:
        """Put the kitchen back into this state."""
        kitchen.scene.restore_state(self.scene)
        kitchen.conditions = set(self.conditions)


class SkillSamplingFailure(SamplingFailure):
    """A sample failed; ``skill_failure`` is the skill's own failure (kind, obstructing objects,
    region) when the skill found no targets, None when the motion or the judge's replay failed."""

    def __init__(
        self, message: str, skill_failure: SkillFailure | None, feedback: tuple[object, ...] = ()
    ) -> None:
        super().__init__(message, feedback)
        self.skill_failure = skill_failure


KITCHEN_BUDGETS: Final = SesameBudgets(max_plans=5, samples_per_step=4, max_samples=120, time_budget_s=900.0)
"""The kitchen's default budgets (the command line's defaults), sized for samples that cost a
motion plan each; the time budget is far above what the sample budgets take, so the seed
alone decides the result."""


@dataclass
class KitchenSampler:
    """Skill + motion back end as the trajectory sampler of every kitchen action."""

    kitchen: KitchenScene
    task: Task
    backend: MotionBackend
    collision_model: str = DEFAULT_COLLISION_MODEL
    feedback: FailureFeedback | None = None
    """Turns skill failures into facts for the abstract search; None: failures teach nothing."""
    drake: DrakeService | None = None
    """Where Drake's models behind the sphere model are asked (None: in this process)."""
    records: dict[int, ActionSampleRecord] = field(default_factory=dict)
    """The refinement record of every trajectory handed out, by ``id`` of its action trajectory."""
    last_record: ActionSampleRecord | None = None
    checkers: PlanningCheckers = field(init=False)
    """The planning collision models, built once per world the refinement meets."""

    def __post_init__(self) -> None:
        self.checkers = PlanningCheckers(self.collision_model, drake=self.drake)

    def atoms_of(self, state: KitchenState) -> frozenset[Atom]:
        """Ψ(x): the atoms true in the snapshot."""
        state.restore(self.kitchen)
        return abstract_state(self.kitchen, self.task.objects)

    def __call__(
        self,
        state: KitchenState,
        transition: AbstractTransition[State, GroundAction],
        rng: np.random.Generator,
    ) -> Trajectory[KitchenState, ActionTrajectory]:
        state.restore(self.kitchen)
        action = transition.action
        trajectory, record = refine_action(
            self.kitchen, 0, action, self.backend, rng, checkers=self.checkers
        )
        self.last_record = record
        if trajectory is None:
            message = record.rejections[-1] if record.rejections else f"{action.text} failed"
            facts: tuple[object, ...] = ()
            if self.feedback is not None and record.skill_failure is not None:
                state.restore(self.kitchen)
                facts = self.feedback.facts(action, transition.source, record.skill_failure)
            raise SkillSamplingFailure(message, record.skill_failure, facts)
        problem = record_conditions(self.kitchen, self.task, action)
        if problem is not None:
            raise SkillSamplingFailure(problem, None)
        self.records[id(trajectory)] = record
        return Trajectory((state, KitchenState.of(self.kitchen)), (trajectory,))


@dataclass(frozen=True, eq=False)
class SesameRefinement:
    """SeSamE's answer for the kitchen: the refined plan (None on failure) and what it cost."""

    refined: RefinedKitchenPlan | None
    result: BilevelResult[KitchenState, ActionTrajectory, State, GroundAction]

    def report_data(self) -> dict[str, object]:
        """The ``bilevel`` section of a report: plans tried, samples, failures, backtracks, and
        (when failures taught the abstract search anything) the facts learned."""
        result = self.result
        learned = {"learned": [fact_text(fact) for fact in result.learned]} if result.learned else {}
        return {
            "planner": result.planner,
            "outcome": str(result.outcome),
            "detail": result.detail,
            "abstract_plans_tried": result.counts.abstract_plans,
            "samples": result.counts.samples,
            "failures": result.counts.failures,
            "backtracks": result.counts.backtracks,
            "plans": [
                {
                    "plan": [a.text for a in attempt.abstract_plan.actions],
                    "outcome": str(attempt.outcome),
                    "steps": [
                        {
                            "action": step.action.text,
                            "samples": step.samples,
                            "failures": step.failures,
                            "backtracks": step.backtracks,
                            "last_failure": step.last_failure,
                        }
                        for step in attempt.steps
                    ],
                }
                for attempt in result.attempts
            ],
            **learned,
        }


@dataclass(frozen=True)
class RefinementOptions:
    """How the kitchen's samples are drawn and what their failures teach."""

    collision_model: str = DEFAULT_COLLISION_MODEL
    """The collision model planning checks moves with (PyBullet always verifies)."""
    feedback: bool = True
    """Confirmed skill failures teach the abstract search (obstructions, places out of reach);
    off, only the refinement of each plan reacts to them (resampling, backtracking)."""
    drake: DrakeService | None = None
    """Where Drake's models behind the sphere model are asked (None: in this process)."""


DEFAULT_OPTIONS: Final = RefinementOptions()


def refine_with_sesame(
    kitchen: KitchenScene,
    task: Task,
    backend: MotionBackend,
    seed: int,
    budgets: SesameBudgets = KITCHEN_BUDGETS,
    options: RefinementOptions = DEFAULT_OPTIONS,
    on_sample: Callable[[SampleEvent[State, GroundAction], ActionSampleRecord | None], None] | None = None,
) -> SesameRefinement:
    """Run SeSamE from the scene as it is; on success the scene is left in the final state.
    ``on_sample(event, record)`` follows every sample (a sample accepted as a step of an abstract
    plan, ``event.succeeded``, has its trajectory in ``record``; a later one with the same or an
    earlier step, or of another plan, takes it back)."""
    teacher = FailureFeedback(kitchen, task, np.random.default_rng(seed)) if options.feedback else None
    sampler = KitchenSampler(kitchen, task, backend, options.collision_model, teacher, options.drake)
    initial = KitchenState.of(kitchen)
    problem = relational_problem(task, initial, sampler.atoms_of, lambda action: sampler)

    def report(event: SampleEvent[State, GroundAction]) -> None:
        if on_sample is not None:
            on_sample(event, sampler.last_record)

    result = sesame(problem, budgets, seed=seed, on_sample=report)
    if result.plan is None:
        initial.restore(kitchen)
        return SesameRefinement(None, result)
    steps = [step.trajectory.actions[0] for step in result.plan.steps]
    records = tuple(
        _renumbered(sampler.records[id(trajectory)], index) for index, trajectory in enumerate(steps)
    )
    result.plan.final_state.restore(kitchen)
    return SesameRefinement(RefinedKitchenPlan(KitchenTrajectory(tuple(steps)), records), result)


def _renumbered(record: ActionSampleRecord, index: int) -> ActionSampleRecord:
    return replace(record, index=index)


def sesame_replanner(
    backend: MotionBackend,
    seed: int,
    budgets: SesameBudgets = KITCHEN_BUDGETS,
    collision_model: str = DEFAULT_COLLISION_MODEL,
) -> Callable[[KitchenScene, Task], KitchenTrajectory | None]:
    """``replan(kitchen, task)`` for execution under physics: SeSamE from the scene as it is
    to the task's goal (its initial state being the scene's), or None if it finds no plan."""

    def replan(kitchen: KitchenScene, task: Task) -> KitchenTrajectory | None:
        options = RefinementOptions(collision_model)
        refined = refine_with_sesame(kitchen, task, backend, seed, budgets, options).refined
        return None if refined is None else refined.trajectory

    return replan
