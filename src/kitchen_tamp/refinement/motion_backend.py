"""Motion back ends of the kitchen pipeline: how one free-space move is solved.

A back end takes a start, a goal, a collision checker and the step's RNG and
returns a ``MotionSolution``: the path (or None) with deterministic figures for
the report and the seconds it took (reported under timing only).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.motion import (
    DEFAULT_MOTION_PLANNER,
    ConfigurationSpace,
    ShortcutHyperparameters,
    check_path_densely,
    path_length,
    planner_named,
    shortcut_path,
)
from kitchen_tamp.motion.collision_checker import CollisionChecker, JointConfiguration
from kitchen_tamp.motion.joint_path import JointPath

Figure = float | int | str | None

DETERMINISM_TIME_BUDGET_S = 600.0
"""Wall-clock budget handed to planners and smoothing: far above what their iteration
limits take, so results depend on the seed only, never on machine speed."""


class BoundedCollisionChecker(CollisionChecker, Protocol):
    """A collision checker that also knows the joint limits."""

    @property
    def lower(self) -> JointConfiguration: ...

    @property
    def upper(self) -> JointConfiguration: ...


@dataclass(frozen=True, eq=False)
class MotionSolution:
    """The answer of a back end for one move."""

    path: JointPath | None
    status: str
    attempts: int
    figures: Mapping[str, Figure] = field(default_factory=dict)
    seconds: float = 0.0
    timings: Mapping[str, float] = field(default_factory=dict)
    """Wall-clock seconds of the back end's parts (for a report's timing section)."""

    @property
    def solved(self) -> bool:
        """Whether a path was found and passed the dense post-check."""
        return self.path is not None


class MotionBackend(Protocol):
    """Solves one free-space move; ``name`` goes into the report."""

    @property
    def name(self) -> str: ...

    def solve(
        self,
        start: JointConfiguration,
        goal: JointConfiguration,
        checker: BoundedCollisionChecker,
        strict_checker: CollisionChecker,
        rng: np.random.Generator,
    ) -> MotionSolution:
        """A path from ``start`` to ``goal`` planned with ``checker`` (which may keep a
        margin) and free under ``strict_checker`` at the judge's resolution (``JUDGE_RESOLUTION_RAD``)."""
        ...


@dataclass(frozen=True)
class SamplingMotionBackend:
    """RRT-Connect (or the single-tree RRT) followed by shortcut smoothing.

    Each attempt uses a fresh seed drawn from the step's RNG; a path counts only
    if, after smoothing, it is also collision-free at ``dense_resolution``
    (planners check edges at 0.01 rad, which can graze obstacles in between).
    """

    planner: str = DEFAULT_MOTION_PLANNER
    """A name of ``kitchen_tamp.motion.MOTION_PLANNERS``."""
    attempts: int = 3
    hyperparameters: Any = None
    """The planner's hyper-parameters (its own type); None: the planner's defaults."""
    shortcut: ShortcutHyperparameters = field(
        default_factory=lambda: ShortcutHyperparameters(max_iterations=60)
    )
    dense_resolution: float = JUDGE_RESOLUTION_RAD

    def __post_init__(self) -> None:
        planner_named(self.planner)  # an UnknownPlannerError (a ValueError) names the choices
        if self.attempts < 1:
            raise ValueError(f"attempts must be at least 1, got {self.attempts}")

    @property
    def name(self) -> str:
        return self.planner

    def solve(
        self,
        start: JointConfiguration,
        goal: JointConfiguration,
        checker: BoundedCollisionChecker,
        strict_checker: CollisionChecker,
        rng: np.random.Generator,
    ) -> MotionSolution:
        clock = time.perf_counter()
        space = ConfigurationSpace(checker.lower, checker.upper)
        totals = {"iterations": 0, "nodes": 0, "collision_checks": 0, "dense_check_failures": 0}
        timings = {"planning_s": 0.0, "smoothing_s": 0.0, "dense_check_s": 0.0}
        status = "not attempted"
        for attempt in range(1, self.attempts + 1):
            seed = int(rng.integers(2**31))
            phase = time.perf_counter()
            result = planner_named(self.planner)(
                start, goal, space, checker, self.hyperparameters, seed=seed,
                time_budget_s=DETERMINISM_TIME_BUDGET_S,
            )
            timings["planning_s"] += time.perf_counter() - phase
            totals["iterations"] += result.iterations
            totals["nodes"] += result.nodes
            totals["collision_checks"] += result.collision_checks
            status = result.status.value
            if result.path is None:
                continue
            raw_length = path_length(result.path)
            phase = time.perf_counter()
            smoothed = shortcut_path(
                result.path, checker, self.shortcut, seed=seed, time_budget_s=DETERMINISM_TIME_BUDGET_S
            )
            timings["smoothing_s"] += time.perf_counter() - phase
            totals["collision_checks"] += smoothed.collision_checks
            phase = time.perf_counter()
            dense = check_path_densely(smoothed.path, strict_checker, self.dense_resolution)
            timings["dense_check_s"] += time.perf_counter() - phase
            totals["collision_checks"] += dense.configurations_checked
            if not dense.collision_free:
                totals["dense_check_failures"] += 1
                status = "path grazes an obstacle between edge checks"
                continue
            path = _at_least_two_waypoints(smoothed.path, start, goal)
            figures: dict[str, Figure] = {
                "planner_seed": seed,
                **totals,
                "raw_path_length_rad": round(raw_length, 9),
                "path_length_rad": round(path_length(path), 9),
                "waypoints": len(path),
            }
            return MotionSolution(path, "solved", attempt, figures, time.perf_counter() - clock, timings)
        return MotionSolution(None, status, self.attempts, dict(totals), time.perf_counter() - clock, timings)


def _at_least_two_waypoints(
    path: JointPath, start: JointConfiguration, goal: JointConfiguration
) -> JointPath:
    """A path a segment can hold: start and goal even when they coincide."""
    if len(path) >= 2:
        return np.asarray(path)
    return np.stack([np.asarray(start, float), np.asarray(goal, float)])
