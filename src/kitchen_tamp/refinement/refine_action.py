"""Refine one action in the kitchen: its skill gives targets, a motion back end connects
the arm to them, and the scene advances to the action's outcome.

This is one sample of the kitchen's trajectory sampler; ``kitchen_sesame``
decides which action to sample next, how often, and when to step back.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.kitchen import KitchenScene, Segment, SkillFailure, sample_action_targets
from kitchen_tamp.kitchen.trajectory import FREE_SPACE_SEGMENT, ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import GroundAction
from kitchen_tamp.refinement.motion_backend import Figure, MotionBackend
from kitchen_tamp.refinement.planning_checkers import DEFAULT_COLLISION_MODEL, planning_checker

DEFAULT_SAMPLES_PER_STEP = 4
"""Target samples (grasp, placement or handle grip) an action may try before it fails."""

PLANNING_MARGIN = 0.003
"""Clearance (m) free-space moves keep while planned: paths are checked every 0.01 rad,
and without slack a path can graze an obstacle between two checks."""


@dataclass(frozen=True)
class StepRecord:
    """What refining one action took. ``figures`` are deterministic for a seed;
    ``seconds`` are wall-clock and belong under a report's timing."""

    index: int
    action: str
    planner: str
    solved: bool
    target_samples: int
    skill_samples: int
    motion_attempts: int
    motion: Mapping[str, Figure]
    waypoints: int
    rejections: tuple[str, ...]
    seconds: Mapping[str, float] = field(default_factory=dict)

    def figures(self) -> dict[str, object]:
        """The record as report data, without wall-clock figures."""
        return {
            "action": self.action,
            "planner": self.planner,
            "solved": self.solved,
            "target_samples": self.target_samples,
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
    records: tuple[StepRecord, ...]


def refine_action(
    kitchen: KitchenScene,
    index: int,
    action: GroundAction,
    backend: MotionBackend,
    rng: np.random.Generator,
    samples_per_step: int = DEFAULT_SAMPLES_PER_STEP,
    planning_margin: float = PLANNING_MARGIN,
    collision_model: str = DEFAULT_COLLISION_MODEL,
) -> tuple[ActionTrajectory | None, StepRecord]:
    """Sample targets for ``action`` and connect the arm to them; on success the scene
    is left in the state after the action. Returns (trajectory or None, record)."""
    rejections: list[str] = []
    skill_samples = motion_attempts = 0
    skills_s = motion_s = 0.0
    backend_s: dict[str, float] = {}
    motion: Mapping[str, Figure] = {}
    for sample in range(1, samples_per_step + 1):
        clock = time.perf_counter()
        try:
            targets = sample_action_targets(kitchen, action, rng)
        except SkillFailure as failure:
            skills_s += time.perf_counter() - clock
            rejections.append(str(failure))
            continue
        skills_s += time.perf_counter() - clock
        skill_samples += targets.samples_tried
        start = kitchen.arm_configuration()
        strict = targets.free_space_checker
        checker = planning_checker(kitchen, targets, planning_margin, collision_model)
        margin = planning_margin
        if not checker.is_valid(np.stack([start, targets.goal_configuration])).all():
            # an end is closer than the margin: plan without slack
            checker, margin = planning_checker(kitchen, targets, 0.0, collision_model), 0.0
        solution = backend.solve(start, targets.goal_configuration, checker, strict, rng)
        motion_s += solution.seconds
        for part, seconds in solution.timings.items():
            backend_s[part] = backend_s.get(part, 0.0) + seconds
        motion_attempts += solution.attempts
        motion = {**solution.figures, "collision_model": collision_model, "planning_margin_m": margin}
        if solution.path is None:
            rejections.append(f"no {backend.name} path to the targets of sample {sample}: {solution.status}")
            continue
        move = Segment(
            FREE_SPACE_SEGMENT,
            solution.path,
            np.full(len(solution.path), targets.gripper_width),
            attached_box=targets.held_box,
        )
        trajectory = ActionTrajectory(action.text, (move, *targets.segments))
        targets.apply(kitchen)
        record = StepRecord(
            index,
            action.text,
            backend.name,
            True,
            sample,
            skill_samples,
            motion_attempts,
            motion,
            trajectory.waypoint_count,
            tuple(rejections),
            {"skills_s": skills_s, "motion_s": motion_s, **backend_s},
        )
        return trajectory, record
    record = StepRecord(
        index,
        action.text,
        backend.name,
        False,
        samples_per_step,
        skill_samples,
        motion_attempts,
        motion,
        0,
        tuple(rejections),
        {"skills_s": skills_s, "motion_s": motion_s, **backend_s},
    )
    return None, record
