"""Refine one action in the kitchen: its skill gives targets, a motion back end connects
the arm to them, the judge's replay of the whole action (``kitchen.replay_action``, at
the judge's resolution with its contact policy) must find nothing, and the scene
advances to the outcome that replay derives -- so an accepted step is one the judge
accepts, and a step it would reject is a failed sample.

This is one sample of the kitchen's trajectory sampler; ``kitchen_sesame``
decides which action to sample next, how often, and when to step back.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.kitchen import KitchenScene, Segment, SkillFailure, replay_action, sample_action_targets
from kitchen_tamp.kitchen.trajectory import FREE_SPACE_SEGMENT, ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import GroundAction
from kitchen_tamp.refinement.motion_backend import Figure, MotionBackend
from kitchen_tamp.refinement.planning_checkers import PlanningCheckers

PLANNING_MARGIN = 0.003
"""Clearance (m) free-space moves keep while planned: paths are checked every 0.01 rad,
and without slack a path can graze an obstacle between two checks."""


@dataclass(frozen=True, kw_only=True)
class ActionSampleRecord:
    """What one sample of an action (its skill's targets, then motion to them) took.
    ``figures`` are deterministic for a seed; ``seconds`` are wall-clock and belong
    under a report's timing."""

    index: int
    action: str
    planner: str
    solved: bool
    skill_samples: int
    motion_attempts: int
    motion: Mapping[str, Figure]
    waypoints: int
    rejections: tuple[str, ...]
    seconds: Mapping[str, float] = field(default_factory=dict)
    skill_failure: SkillFailure | None = None
    """The skill's failure when it found no targets (kind, obstructing objects, region): for
    the planner, not the report."""
    trajectory: ActionTrajectory | None = None
    """The sample's trajectory (None when it failed): for the planner and whoever follows it, not
    the report."""

    def figures(self) -> dict[str, object]:
        """The record as report data, without wall-clock figures."""
        return {
            "action": self.action,
            "planner": self.planner,
            "solved": self.solved,
            "skill_samples": self.skill_samples,
            "motion_attempts": self.motion_attempts,
            "motion": dict(self.motion),
            "waypoints": self.waypoints,
            "rejections": list(self.rejections),
        }


@dataclass(frozen=True, eq=False)
class RefinedKitchenPlan:
    """A refined plan and one record per action."""

    trajectory: KitchenTrajectory
    records: tuple[ActionSampleRecord, ...]


def refine_action(
    kitchen: KitchenScene,
    index: int,
    action: GroundAction,
    backend: MotionBackend,
    rng: np.random.Generator,
    planning_margin: float = PLANNING_MARGIN,
    checkers: PlanningCheckers | None = None,
) -> tuple[ActionTrajectory | None, ActionSampleRecord]:
    """One sample of ``action``: sample its skill's targets and connect the arm to them.
    On success the scene is left in the state after the action. Returns (trajectory or
    None, record); resampling and stepping back are the caller's (SeSamE's) business.
    ``checkers`` builds the planning models (of its collision model), reusing those of a world
    seen before; None: the default model's, built for this sample alone."""
    if checkers is None:
        checkers = PlanningCheckers()
    collision_model = checkers.model
    clock = time.perf_counter()
    try:
        targets = sample_action_targets(kitchen, action, rng)
    except SkillFailure as failure:
        seconds = {"skills_s": time.perf_counter() - clock, "motion_s": 0.0}
        return None, ActionSampleRecord(
            index=index,
            action=action.text,
            planner=backend.name,
            solved=False,
            skill_samples=0,
            motion_attempts=0,
            motion={},
            waypoints=0,
            rejections=(str(failure),),
            seconds=seconds,
            skill_failure=failure,
        )
    skills_s = time.perf_counter() - clock
    start, clock = kitchen.arm_configuration(), time.perf_counter()
    checker = checkers.checker(kitchen, targets, planning_margin)
    margin = planning_margin
    if not checker.is_valid(np.stack([start, targets.goal_configuration])).all():
        # an end is closer than the margin: plan without slack
        checker, margin = checkers.checker(kitchen, targets, 0.0), 0.0
    strict = checkers.strict(targets, checker)
    checkers_s = time.perf_counter() - clock
    solution = backend.solve(start, targets.goal_configuration, checker, strict, rng)
    motion = {**solution.figures, "collision_model": collision_model, "planning_margin_m": margin}
    seconds = {"skills_s": skills_s, "checkers_s": checkers_s, "motion_s": solution.seconds,
               **solution.timings}

    def record(trajectory: ActionTrajectory | None, rejection: str | None) -> ActionSampleRecord:
        return ActionSampleRecord(
            index=index,
            action=action.text,
            planner=backend.name,
            solved=trajectory is not None,
            skill_samples=targets.samples_tried,
            motion_attempts=solution.attempts,
            motion=motion,
            waypoints=0 if trajectory is None else trajectory.waypoint_count,
            rejections=() if rejection is None else (rejection,),
            seconds=seconds,
            trajectory=trajectory,
        )

    if solution.path is None:
        return None, record(None, f"no {backend.name} path to the targets of sample 1: {solution.status}")
    move = Segment(FREE_SPACE_SEGMENT, solution.path, np.full(len(solution.path), targets.gripper_width))
    trajectory = ActionTrajectory(action.text, (move, *targets.segments))
    before, clock = kitchen.scene.save_state(), time.perf_counter()
    judged = replay_action(kitchen, action.text, action.args, trajectory.segments, measure=False)
    seconds["judge_replay_s"] = time.perf_counter() - clock
    if judged.problems:
        kitchen.scene.restore_state(before)
        return None, record(None, f"the judge's replay of sample 1 rejects it: {judged.problems[0]}")
    return trajectory, record(trajectory, None)
