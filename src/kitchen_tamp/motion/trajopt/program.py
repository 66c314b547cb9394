"""Build step of trajectory optimisation: a Drake MathematicalProgram over N waypoints.

Decision variables are N x d joint waypoints. The cost is the sum of squared
joint differences between consecutive waypoints; the first and last are held
equal to start and goal; every waypoint stays within the joint limits; each
step changes every joint by at most `max_step`; and every interior waypoint,
and `samples_between_waypoints` points on each step, keep a clearance of at
least `collision_margin` (start and goal, being fixed, need only be
collision-free, so they may be closer than the margin). The clearance (and its
gradient) comes from the caller as a `Clearance`, a batched function, so that
the kitchen can plug in Drake's SceneGraph (`one_at_a_time` around a signed
distance), the sphere model's smooth clearance, or any other collision model.

The collision constraints are grouped in runs of `waypoints_per_constraint`
consecutive steps: Drake calls one Python function per constraint and
iteration, with every variable as an AutoDiffXd, which costs far more than a
batched clearance of the run's twenty-odd configurations; each run declares
its Jacobian's sparsity (a row depends on the one or two waypoints it mixes).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from pydrake.autodiffutils import ExtractGradient, ExtractValue, InitializeAutoDiff
from pydrake.solvers import MathematicalProgram

from kitchen_tamp.motion.collision_checker import JointConfiguration, JointConfigurations
from kitchen_tamp.motion.configuration_space import ConfigurationSpace, InvalidMotionQueryError
from kitchen_tamp.motion.joint_path import JointPath, resample_path
from kitchen_tamp.motion.trajopt.settings import TrajectoryOptimizationSettings

FloatArray = npt.NDArray[np.float64]

SignedDistanceFunction = Callable[[JointConfiguration], tuple[float, JointConfiguration]]
"""q (d,) -> (minimum signed distance over all collision pairs, its gradient (d,))."""
Clearance = Callable[[JointConfigurations], tuple[FloatArray, FloatArray]]
"""qs (M, d) -> (clearance of each row (M,), negative in collision, and its gradients (M, d)): a
signed distance, or any smooth stand-in that is at least the margin only when the margin is kept."""


def one_at_a_time(signed_distance: SignedDistanceFunction) -> Clearance:
    """A `Clearance` that asks ``signed_distance`` for each configuration in turn."""

    def clearance(qs: JointConfigurations) -> tuple[FloatArray, FloatArray]:
        answers = [signed_distance(np.asarray(q, dtype=np.float64)) for q in qs]
        values = np.array([value for value, _ in answers], dtype=np.float64)
        gradients = np.array([gradient for _, gradient in answers], dtype=np.float64)
        return values, gradients.reshape(len(qs), -1)

    return clearance


class ClearanceConstraint:
    """The collision constraints on one run of consecutive waypoints, evaluated in one call.

    Rows are the run's interior waypoints and its points between waypoints, each a fixed
    combination (``weights``, rows x waypoints of the run) of the run's waypoints; one call of the
    `Clearance` answers them all. Drake passes the run's waypoints stacked, as floats or as
    AutoDiffXd; the gradient of a row is its clearance gradient spread over the (at most two)
    waypoints it mixes. ``evaluations`` counts configurations evaluated (shared by all runs).
    """

    def __init__(self, clearance: Clearance, weights: FloatArray, counter: list[int]) -> None:
        self.clearance = clearance
        self.weights = weights
        self._counter = counter

    def sparsity(self, dimension: int) -> list[tuple[int, int]]:
        """(row, variable) pairs of the Jacobian that can be non-zero."""
        return [
            (row, waypoint * dimension + joint)
            for row, waypoint in zip(*np.nonzero(self.weights), strict=True)
            for joint in range(dimension)
        ]

    def __call__(self, stacked: npt.NDArray[Any]) -> npt.NDArray[Any]:
        count = self.weights.shape[1]
        if stacked.dtype != object:
            configurations = self.weights @ np.asarray(stacked, dtype=np.float64).reshape(count, -1)
            self._counter[0] += len(configurations)
            return self.clearance(configurations)[0]
        values = np.asarray(ExtractValue(stacked), dtype=np.float64).reshape(count, -1)
        configurations = self.weights @ values
        self._counter[0] += len(configurations)
        clearances, gradients = self.clearance(configurations)
        dimension = values.shape[1]
        derivatives = np.asarray(ExtractGradient(stacked), dtype=np.float64)
        per_waypoint = derivatives.reshape(count, dimension, -1)  # (waypoints, joints, derivatives)
        mixed = np.einsum("rw,wjk->rjk", self.weights, per_waypoint)
        chained = np.einsum("rj,rjk->rk", gradients, mixed)
        initialize: Any = InitializeAutoDiff  # pydrake's stubs misspell the array type
        answer: npt.NDArray[Any] = initialize(clearances, chained)
        return answer.reshape(-1)


@dataclass(frozen=True, eq=False)
class TrajectoryProgram:
    """A built program: its waypoint variables (N, d), initial guess and constraint evaluator."""

    program: MathematicalProgram
    waypoints: npt.NDArray[Any]
    initial_guess: JointPath
    constraints: tuple[ClearanceConstraint, ...]
    settings: TrajectoryOptimizationSettings
    evaluation_counter: list[int]
    """One cell: configurations whose clearance the solver asked for so far."""

    @property
    def collision_evaluations(self) -> int:
        return self.evaluation_counter[0]


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


def _collision_rows(count: int, samples_between_waypoints: int, first: int, last: int) -> FloatArray:
    """Weights (rows, last - first + 1) of the collision points on steps first..last-1: each
    interior waypoint, then the points between it and the next."""
    fractions = np.arange(1, samples_between_waypoints + 1) / (samples_between_waypoints + 1)
    rows: list[FloatArray] = []
    width = last - first + 1
    for index in range(first, last):
        if 0 < index < count - 1:  # start and goal are fixed: they need only be collision-free
            row = np.zeros(width)
            row[index - first] = 1.0
            rows.append(row)
        for fraction in fractions:
            row = np.zeros(width)
            row[index - first], row[index + 1 - first] = 1.0 - fraction, fraction
            rows.append(row)
    return np.array(rows).reshape(-1, width)


def build_trajectory_program(
    start: npt.ArrayLike,
    goal: npt.ArrayLike,
    space: ConfigurationSpace,
    clearance: Clearance,
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
    identity = np.eye(dimension)
    step_matrix = np.hstack([-identity, identity])
    # One small cost per step, not one over all waypoints: solvers evaluate a cost's gradient
    # through AutoDiffXd, which costs the cube of its variable count.
    squared_step = 2.0 * step_matrix.T @ step_matrix
    for index in range(count - 1):
        pair = np.concatenate([waypoints[index], waypoints[index + 1]])
        program.AddQuadraticCost(squared_step, np.zeros(2 * dimension), pair, is_convex=True)
    program.AddLinearEqualityConstraint(identity, q_start, waypoints[0])
    program.AddLinearEqualityConstraint(identity, q_goal, waypoints[-1])
    program.AddBoundingBoxConstraint(
        np.tile(space.lower, count), np.tile(space.upper, count), waypoints.reshape(-1)
    )
    step_bound = np.full(dimension, settings.max_step)
    for index in range(count - 1):
        pair = np.concatenate([waypoints[index], waypoints[index + 1]])
        program.AddLinearConstraint(step_matrix, -step_bound, step_bound, pair)
    counter = [0]
    constraints = []
    run = settings.waypoints_per_constraint
    for first in range(0, count - 1, run):
        last = min(first + run, count - 1)
        weights = _collision_rows(count, settings.samples_between_waypoints, first, last)
        if len(weights) == 0:
            continue
        constraint = ClearanceConstraint(clearance, weights, counter)
        binding = program.AddConstraint(
            constraint,
            np.full(len(weights), settings.collision_margin),
            np.full(len(weights), np.inf),
            waypoints[first : last + 1].reshape(-1),
            description=f"clearance_{first}-{last}",
        )
        binding.evaluator().SetGradientSparsityPattern(constraint.sparsity(dimension))
        constraints.append(constraint)
    guess = initial_waypoints(q_start, q_goal, count, initial_path)
    program.SetInitialGuess(waypoints, guess)
    return TrajectoryProgram(program, waypoints, guess, tuple(constraints), settings, counter)
