"""Trajectory optimisation as a motion back end (``final_project.py optimizes``).

Each free-space move is solved by the Drake program of
``kitchen_tamp.motion.trajopt.program``: N joint waypoints, shortest squared
path, start/goal equalities, joint limits, a bound on each step and a clearance
of at least the margin at every interior waypoint and at points between
waypoints. An RRT-Connect + shortcut path for the same move is planned first
(with a seed drawn from the step's RNG; its length is also the yardstick the
report compares against). The initial guess is the straight line in joint space
when the planning checker finds it free, else that path. Attempts, in order,
until one both solves and passes the dense PyBullet re-check:

1. the sphere model's smooth clearance (`sphere_clearance`: every sphere pair,
   compiled, a few microseconds per configuration), when the planning checker
   has a sphere model;
2. the same with twice the waypoints and more points between them, from the
   RRT-Connect path;
3. Drake's exact signed distance (the minimum over pairs of the same scene's
   convex hulls), from the same initial guess.

Without a sphere model (``--collision-model drake``): Drake's signed distance,
then twice the waypoints from the RRT-Connect path. If none verifies the move
fails; nothing falls back silently to the sampled path.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Protocol

import numpy as np
import numpy.typing as npt

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.motion import ConfigurationSpace, InvalidMotionQueryError, check_path_densely, path_length
from kitchen_tamp.motion.collision_checker import CollisionChecker, JointConfiguration
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.trajopt.program import Clearance, one_at_a_time
from kitchen_tamp.motion.trajopt.settings import TrajectoryOptimizationSettings
from kitchen_tamp.motion.trajopt.solver import nonlinear_solver, optimize_trajectory
from kitchen_tamp.refinement.motion_backend import (
    BoundedCollisionChecker,
    Figure,
    MotionSolution,
    SamplingMotionBackend,
)
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS

Attempt = tuple[bool, TrajectoryOptimizationSettings, str]
"""One attempt of a move: (starts from the reference path, settings, clearance model)."""


class SignedDistanceModel(BoundedCollisionChecker, Protocol):
    """A planning checker that also gives the minimum signed distance and its gradient."""

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]: ...


@dataclass(frozen=True)
class OptimizingMotionBackend:
    """Drake trajectory optimisation with an RRT-Connect warm start as the second attempt."""

    settings: TrajectoryOptimizationSettings = DEFAULT_SETTINGS
    reference: SamplingMotionBackend = field(default_factory=SamplingMotionBackend)
    dense_resolution: float = JUDGE_RESOLUTION_RAD

    @property
    def name(self) -> str:
        return "trajectory_optimization"

    @property
    def solver_name(self) -> str:
        """The nonlinear solver Drake uses (SNOPT when the wheel has it, else IPOPT)."""
        return str(nonlinear_solver().solver_id().name())

    def solve(
        self,
        start: JointConfiguration,
        goal: JointConfiguration,
        checker: BoundedCollisionChecker,
        strict_checker: CollisionChecker,
        rng: np.random.Generator,
    ) -> MotionSolution:
        signed_distance = getattr(checker, "signed_distance", None)
        if signed_distance is None:
            raise ValueError("trajectory optimisation needs a collision model with signed distances (drake)")
        clock = time.perf_counter()
        reference: MotionSolution | None = None

        def planned_reference() -> MotionSolution:
            nonlocal reference
            if reference is None:
                reference = self.reference.solve(start, goal, checker, strict_checker, rng)
            return reference

        space = ConfigurationSpace(checker.lower, checker.upper)
        attempts: list[dict[str, Figure]] = []
        optimisation_s = 0.0
        clearances = {"drake": one_at_a_time(signed_distance)}
        spheres = _sphere_clearance(checker, self.settings.collision_margin, np.stack([start, goal]))
        if spheres is not None:
            clearances["spheres"] = spheres
        straight_free = bool(checker.segment_valid(start, goal))
        for from_reference, settings, model in self._plans(straight_free, spheres is not None):
            if from_reference and planned_reference().path is None and attempts:
                continue  # no path to warm-start from, and the straight line was tried
            initial, guide = "straight line", None
            if from_reference and (path := planned_reference().path) is not None:
                seed = planned_reference().figures.get("planner_seed")
                initial, guide = f"rrt_connect seed {seed}", path
            if settings.num_waypoints != self.settings.num_waypoints:
                initial += f", {settings.num_waypoints} waypoints"
            clearance = clearances[model]
            attempt, waypoints, seconds = self._attempt(start, goal, space, clearance, settings, guide)
            optimisation_s += seconds
            number = len(attempts) + 1
            attempt = {"attempt": number, "initial_guess": initial, "clearance": model, **attempt}
            if waypoints is not None:
                dense = check_path_densely(waypoints, strict_checker, self.dense_resolution)
                attempt["dense_check"] = "free" if dense.collision_free else "collides between waypoints"
            attempts.append(attempt)
            if waypoints is not None and attempt["dense_check"] == "free":
                figures = self._figures(waypoints, reference, attempts, settings)
                return MotionSolution(
                    waypoints,
                    "solved",
                    number,
                    figures,
                    time.perf_counter() - clock,
                    self._timings(optimisation_s, reference),
                )
        figures = self._figures(None, reference, attempts, self.settings)
        status = str(attempts[-1].get("status", "not attempted")) if attempts else "not attempted"
        return MotionSolution(
            None,
            status,
            len(attempts),
            figures,
            time.perf_counter() - clock,
            self._timings(optimisation_s, reference),
        )

    def _plans(self, straight_free: bool, spheres: bool) -> list[Attempt]:
        """The attempts in order: (whether it starts from the reference path, settings, clearance
        model). The first starts from the straight line when the planning checker finds it free,
        else from the reference path: optimising through an obstacle is where SNOPT spent tens of
        thousands of distance queries, and a free straight line needs no reference at all. With a
        sphere model: its clearance, then its clearance with twice the waypoints from the
        reference path (for a path that grazed between waypoints), then Drake's exact signed
        distance (where the spheres' overshoot closes a passage). Without: Drake's, then twice the
        waypoints."""
        denser = replace(
            self.settings,
            num_waypoints=2 * self.settings.num_waypoints,
            samples_between_waypoints=self.settings.samples_between_waypoints + 1,
        )
        first = not straight_free
        if spheres:
            return [
                (first, self.settings, "spheres"),
                (True, denser, "spheres"),
                (first, self.settings, "drake"),
            ]
        return [(first, self.settings, "drake"), (True, denser, "drake")]

    @staticmethod
    def _timings(optimisation_s: float, reference: MotionSolution | None) -> dict[str, float]:
        return {
            "optimization_s": optimisation_s,
            "reference_rrt_s": 0.0 if reference is None else reference.seconds,
        }

    def _attempt(
        self,
        start: JointConfiguration,
        goal: JointConfiguration,
        space: ConfigurationSpace,
        clearance: Clearance,
        settings: TrajectoryOptimizationSettings,
        guide: JointPath | None,
    ) -> tuple[dict[str, Figure], JointPath | None, float]:
        """One solve: (figures, waypoints if the solver succeeded, seconds)."""
        needed = int(np.ceil(float(np.max(np.abs(goal - start))) / settings.max_step)) + 1
        if needed > settings.num_waypoints:
            settings = replace(settings, num_waypoints=needed)
        try:
            result = optimize_trajectory(start, goal, space, clearance, settings, initial_path=guide)
        except InvalidMotionQueryError as error:
            return {"status": str(error)}, None, 0.0
        figures: dict[str, Figure] = {
            "status": result.solution_status,
            "solver_success": result.success,
            "cost": round(result.cost, 9) if np.isfinite(result.cost) else None,
            "collision_evaluations": result.collision_evaluations,
            "waypoints": settings.num_waypoints,
        }
        return figures, (result.waypoints if result.success else None), result.solve_time_s

    def _figures(
        self,
        path: JointPath | None,
        reference: MotionSolution | None,
        attempts: list[dict[str, Figure]],
        settings: TrajectoryOptimizationSettings,
    ) -> dict[str, Figure]:
        """The move's report figures; the RRT-Connect comparison only when the reference was planned
        (not when the free straight line was the answer)."""
        planned = reference is not None and reference.path is not None
        rrt_length = reference.figures.get("path_length_rad") if planned and reference else None
        length = round(path_length(path), 9) if path is not None else None
        ratio = (
            round(length / float(rrt_length), 6)
            if length is not None and isinstance(rrt_length, float) and rrt_length > 0
            else None
        )
        return {
            "solver": self.solver_name,
            "collision_margin_m": settings.collision_margin,
            "attempts": attempts,  # type: ignore[dict-item]
            "waypoints": None if path is None else len(path),
            "path_length_rad": length,
            "rrt_connect_planned": reference is not None,
            "rrt_connect_path_length_rad": rrt_length,
            "length_ratio_to_rrt_connect": ratio,
            "rrt_connect_seed": None if reference is None else reference.figures.get("planner_seed"),
        }

def _sphere_clearance(
    checker: BoundedCollisionChecker, margin: float, ends: npt.NDArray[np.float64]
) -> Clearance | None:
    """The smooth clearance of the checker's sphere model (a `SphereScreenedChecker`'s
    ``spheres``) for a move between ``ends``, or None when it plans without one."""
    model = getattr(getattr(checker, "spheres", None), "model", None)
    if model is None:
        return None
    # imported here: numba loads only when the sphere model is used
    from kitchen_tamp.motion.geometry.spheres.clearance import SphereClearance

    return SphereClearance(model, margin, ends=ends)
