"""Build step of trajectory optimisation: a Drake MathematicalProgram over N waypoints.

Decision variables are N x d joint waypoints. The cost is the sum of squared
joint differences between consecutive waypoints; the first and last are held
equal to start and goal; every waypoint stays within the joint limits; each
step changes every joint by at most `max_step`; and every interior waypoint,
and `samples_between_waypoints` points on each step, keep a minimum signed
distance of at least `collision_margin` (start and goal, being fixed, need only
be collision-free, so they may be closer than the margin), using a signed
distance (and its gradient) supplied by the caller, so that the kitchen can
plug in Drake's SceneGraph or any other collision model.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from pydrake.autodiffutils import AutoDiffXd, ExtractGradient, ExtractValue
from pydrake.solvers import MathematicalProgram

from kitchen_tamp.motion.collision_checker import JointConfiguration
from kitchen_tamp.motion.configuration_space import ConfigurationSpace, InvalidMotionQueryError
from kitchen_tamp.motion.joint_path import JointPath, resample_path

SignedDistanceFunction = Callable[[JointConfiguration], tuple[float, JointConfiguration]]
"""q (d,) -> (minimum signed distance over all collision pairs, its gradient (d,))."""


@dataclass(frozen=True)
class TrajectoryOptimizationSettings:
    """Shape and constraints of the program (radians, and the signed distance's units)."""

    num_waypoints: int = 50
    max_step: float = 0.1
    collision_margin: float = 0.01
    max_iterations: int = 1000
    optimality_tolerance: float | None = None
    """Solver's optimality tolerance (SNOPT "Major optimality tolerance", IPOPT "tol");
    None keeps the solver's default."""
    feasibility_tolerance: float | None = None
    """SNOPT's "Major feasibility tolerance" (IPOPT "constr_viol_tol"); None keeps the default."""
    samples_between_waypoints: int = 1
    """Extra collision constraints on each step, at evenly spaced points between two waypoints:
    the straight segment between waypoints is what gets executed and verified."""

    def __post_init__(self) -> None:
        if self.num_waypoints < 2:
            raise ValueError(f"num_waypoints must be at least 2, got {self.num_waypoints}")
        if self.max_step <= 0.0:
            raise ValueError(f"max_step must be positive, got {self.max_step}")
        if self.max_iterations < 1:
            raise ValueError(f"max_iterations must be at least 1, got {self.max_iterations}")
        if self.samples_between_waypoints < 0:
            raise ValueError(f"samples_between_waypoints must be >= 0, got {self.samples_between_waypoints}")


class SignedDistanceConstraint:
    """Evaluates a `SignedDistanceFunction` for Drake on floats or AutoDiffXd, counting calls."""

    def __init__(self, signed_distance: SignedDistanceFunction) -> None:
        self.signed_distance = signed_distance
        self.evaluations = 0

    def between(self, fraction: float) -> Callable[[npt.NDArray[Any]], npt.NDArray[Any]]:
        """The constraint at ``(1 - fraction) q_a + fraction q_b`` of the stacked pair ``[q_a, q_b]``."""

        def evaluate(pair: npt.NDArray[Any]) -> npt.NDArray[Any]:
            half = len(pair) // 2
            return self((1.0 - fraction) * pair[:half] + fraction * pair[half:])

        return evaluate

    def __call__(self, q: npt.NDArray[Any]) -> npt.NDArray[Any]:
        self.evaluations += 1
        if q.dtype != object:
            value, _ = self.signed_distance(np.asarray(q, dtype=np.float64))
            return np.array([value])
        q_value = np.asarray(ExtractValue(q), dtype=np.float64).reshape(-1)
        value, gradient = self.signed_distance(q_value)
        chained = np.asarray(gradient, dtype=np.float64) @ ExtractGradient(q)
        return np.array([AutoDiffXd(float(value), chained)], dtype=object)


@dataclass(frozen=True, eq=False)
class TrajectoryProgram:
    """A built program: its waypoint variables (N, d), initial guess and constraint evaluator."""

    program: MathematicalProgram
    waypoints: npt.NDArray[Any]
    initial_guess: JointPath
    collision_constraint: SignedDistanceConstraint
    settings: TrajectoryOptimizationSettings


def initial_waypoints(
    start: JointConfiguration,
    goal: JointConfiguration,
    num_waypoints: int,
    path: JointPath | None = None,
) -> JointPath:
    """The straight line from start to goal, or `path`, resampled to `num_waypoints`."""
    guide = np.stack([start, goal]) if path is None else np.asarray(path, dtype=np.float64)
    waypoints = resample_path(guide, num_waypoints)
    waypoints[0], waypoints[-1] = start, goal
    return waypoints


def build_trajectory_program(
    start: npt.ArrayLike,
    goal: npt.ArrayLike,
    space: ConfigurationSpace,
    signed_distance: SignedDistanceFunction,
    settings: TrajectoryOptimizationSettings | None = None,
    initial_path: JointPath | None = None,
) -> TrajectoryProgram:
    """Build the program; `initial_path` (e.g. an RRT-Connect path) warm-starts it.

    Raises `InvalidMotionQueryError` for a malformed start/goal, or when the
    step bound cannot reach the goal in `num_waypoints - 1` steps.
    """
    settings = settings or TrajectoryOptimizationSettings()
    q_start = space.validated(start, "start")
    q_goal = space.validated(goal, "goal")
    count, dimension = settings.num_waypoints, space.dimension
    steps_needed = float(np.max(np.abs(q_goal - q_start))) / settings.max_step
    if steps_needed > count - 1:
        raise InvalidMotionQueryError(
            f"goal is {steps_needed:.1f} steps of max_step={settings.max_step} away, more than "
            f"{count - 1}; raise num_waypoints or max_step"
        )

    # Typed as Any: pydrake's stubs spell arrays ndarray[float64, ...], which
    # numpy's generic ndarray[shape, dtype] rejects for every float array.
    program: Any = MathematicalProgram()
    waypoints = program.NewContinuousVariables(count, dimension, "q")
    differences = np.diff(np.eye(count), axis=0)  # (N - 1, N): row k is q[k+1] - q[k]
    squared_steps = np.kron(differences.T @ differences, np.eye(dimension))
    program.AddQuadraticCost(
        2.0 * squared_steps, np.zeros(count * dimension), waypoints.reshape(-1), is_convex=True
    )
    identity = np.eye(dimension)
    program.AddLinearEqualityConstraint(identity, q_start, waypoints[0])
    program.AddLinearEqualityConstraint(identity, q_goal, waypoints[-1])
    program.AddBoundingBoxConstraint(
        np.tile(space.lower, count), np.tile(space.upper, count), waypoints.reshape(-1)
    )
    step_matrix = np.hstack([-identity, identity])
    step_bound = np.full(dimension, settings.max_step)
    collision_constraint = SignedDistanceConstraint(signed_distance)
    margin = np.array([settings.collision_margin])
    fractions = np.arange(1, settings.samples_between_waypoints + 1) / (
        settings.samples_between_waypoints + 1
    )
    for index in range(count):
        if index + 1 < count:
            pair = np.concatenate([waypoints[index], waypoints[index + 1]])
            program.AddLinearConstraint(step_matrix, -step_bound, step_bound, pair)
            for fraction in fractions:
                program.AddConstraint(
                    collision_constraint.between(float(fraction)),
                    margin,
                    np.array([np.inf]),
                    pair,
                    description=f"signed_distance_{index}+{fraction:.2f}",
                )
        if 0 < index < count - 1:  # start and goal are fixed: they need only be collision-free
            program.AddConstraint(
                collision_constraint,
                margin,
                np.array([np.inf]),
                waypoints[index],
                description=f"signed_distance_{index}",
            )
    guess = initial_waypoints(q_start, q_goal, count, initial_path)
    program.SetInitialGuess(waypoints, guess)
    return TrajectoryProgram(program, waypoints, guess, collision_constraint, settings)
