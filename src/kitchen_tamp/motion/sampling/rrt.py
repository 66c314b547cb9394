"""Goal-biased RRT, as in the class project: one tree grown from the start."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from kitchen_tamp.joint_spacing import PLANNING_RESOLUTION_RAD
from kitchen_tamp.motion.collision_checker import CollisionChecker, JointConfiguration
from kitchen_tamp.motion.configuration_space import ConfigurationSpace
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.planning_result import (
    PlanningResult,
    PlanStatus,
    endpoint_collision_status,
)
from kitchen_tamp.motion.sampling.configuration_tree import ConfigurationTree
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker


@dataclass(frozen=True)
class RrtHyperparameters:
    """Goal bias, step, edge-check resolution and goal region of `plan_rrt` (radians)."""

    goal_bias: float = 0.2
    step_size: float = float(np.deg2rad(5.0))
    edge_resolution: float = PLANNING_RESOLUTION_RAD
    goal_tolerance: float = float(np.deg2rad(1.0))
    max_iterations: int = 10_000

    def __post_init__(self) -> None:
        if not 0.0 <= self.goal_bias <= 1.0:
            raise ValueError(f"goal_bias must be in [0, 1], got {self.goal_bias}")
        if self.step_size <= 0.0:
            raise ValueError(f"step_size must be positive, got {self.step_size}")
        if self.edge_resolution <= 0.0:
            raise ValueError(f"edge_resolution must be positive, got {self.edge_resolution}")
        if self.goal_tolerance < 0.0:
            raise ValueError(f"goal_tolerance must be non-negative, got {self.goal_tolerance}")
        if self.max_iterations < 1:
            raise ValueError(f"max_iterations must be at least 1, got {self.max_iterations}")


def steer(q_from: JointConfiguration, q_toward: JointConfiguration, step_size: float) -> JointConfiguration:
    """The configuration at most `step_size` from `q_from` on the way to `q_toward`."""
    direction = q_toward - q_from
    distance = float(np.linalg.norm(direction))
    if distance <= step_size:
        return q_toward.copy()
    return np.asarray(q_from + direction * (step_size / distance))


def plan_rrt(
    start: npt.ArrayLike,
    goal: npt.ArrayLike,
    space: ConfigurationSpace,
    checker: CollisionChecker,
    hyperparameters: RrtHyperparameters | None = None,
    *,
    seed: int = 0,
    time_budget_s: float = 10.0,
) -> PlanningResult:
    """Grow a tree from `start`, sampling `goal` with probability `goal_bias`.

    A node within `goal_tolerance` of the goal in every joint is joined to the
    goal exactly, so the path ends at `goal`. Raises `InvalidMotionQueryError`
    for a malformed or out-of-bounds start/goal; a start or goal in collision
    is reported by the result's status.
    """
    params = hyperparameters or RrtHyperparameters()
    clock_start = time.perf_counter()
    deadline = clock_start + time_budget_s
    q_start = space.validated(start, "start")
    q_goal = space.validated(goal, "goal")
    rng = np.random.default_rng(seed)
    segments = CountingSegmentChecker(checker, params.edge_resolution)
    tree = ConfigurationTree(q_start)

    def finish(status: PlanStatus, iterations: int, path: JointPath | None = None) -> PlanningResult:
        return PlanningResult(
            status=status,
            path=path,
            iterations=iterations,
            nodes=len(tree),
            collision_checks=segments.configurations_checked,
            planning_time_s=time.perf_counter() - clock_start,
        )

    endpoint_status = endpoint_collision_status(segments, q_start, q_goal)
    if endpoint_status is not None:
        return finish(endpoint_status, 0)

    for iteration in range(1, params.max_iterations + 1):
        if time.perf_counter() >= deadline:
            return finish(PlanStatus.TIME_LIMIT, iteration - 1)
        target = q_goal if rng.random() < params.goal_bias else space.sample_uniform(rng, 1)[0]
        near = tree.nearest(target)
        q_near = tree.node(near)
        q_new = steer(q_near, target, params.step_size)
        if not segments.segment_valid(q_near, q_new, check_start=False):
            continue
        new = tree.add(q_new, near)
        if np.all(np.abs(q_new - q_goal) <= params.goal_tolerance) and segments.segment_valid(
            q_new, q_goal, check_start=False, check_end=False
        ):
            if not np.array_equal(q_new, q_goal):
                new = tree.add(q_goal, new)
            return finish(PlanStatus.SOLVED, iteration, tree.path_from_root(new))
    return finish(PlanStatus.ITERATION_LIMIT, params.max_iterations)
