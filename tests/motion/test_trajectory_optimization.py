from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pytest

from kitchen_tamp.motion import (
    ConfigurationSpace,
    InvalidMotionQueryError,
    RrtConnectHyperparameters,
    plan_rrt_connect,
)
from kitchen_tamp.motion.path_verification import check_path_densely
from kitchen_tamp.motion.trajopt.program import (
    TrajectoryOptimizationSettings,
    build_trajectory_program,
    one_at_a_time,
)
from kitchen_tamp.motion.trajopt.solver import (
    nonlinear_solver,
    optimize_trajectory,
    reconstruct_trajectory,
    solve_trajectory_program,
)
from tests.motion.toy_worlds import BoxBallWorld

SPACE = ConfigurationSpace(np.full(2, -1.0), np.full(2, 2.0))
CENTER, RADIUS = np.array([0.5, 0.03]), 0.25
START, GOAL = np.array([0.0, 0.0]), np.array([1.0, 0.0])
SETTINGS = TrajectoryOptimizationSettings(num_waypoints=30, max_step=0.1, collision_margin=0.02)
WORLD = BoxBallWorld(balls=[(CENTER, RADIUS)])


def disc_signed_distance(q: npt.NDArray[np.float64]) -> tuple[float, npt.NDArray[np.float64]]:
    offset = q - CENTER
    distance = float(np.linalg.norm(offset))
    return distance - RADIUS, offset / max(distance, 1e-12)


DISC_CLEARANCE = one_at_a_time(disc_signed_distance)


def test_optimum_avoids_the_disc_the_straight_line_hits() -> None:
    assert not check_path_densely(np.stack([START, GOAL]), WORLD, 1e-3).collision_free
    result = optimize_trajectory(START, GOAL, SPACE, DISC_CLEARANCE, SETTINGS)
    assert result.success, result.solution_status
    assert result.waypoints.shape == (30, 2)
    np.testing.assert_allclose(result.waypoints[0], START, atol=1e-9)
    np.testing.assert_allclose(result.waypoints[-1], GOAL, atol=1e-9)
    assert check_path_densely(result.waypoints, WORLD, 1e-3).collision_free
    steps = np.abs(np.diff(result.waypoints, axis=0))
    assert np.all(steps <= SETTINGS.max_step + 1e-6)
    assert result.solver_name == nonlinear_solver().solver_id().name()
    assert result.collision_evaluations > 0
    straight_line_cost = 29 * (1.0 / 29) ** 2
    assert straight_line_cost < result.cost < 3 * straight_line_cost


def test_build_solve_reconstruct_is_deterministic() -> None:
    results = []
    for _ in range(2):
        problem = build_trajectory_program(START, GOAL, SPACE, DISC_CLEARANCE, SETTINGS)
        results.append(reconstruct_trajectory(problem, solve_trajectory_program(problem), 0.0))
    np.testing.assert_array_equal(results[0].waypoints, results[1].waypoints)
    assert results[0].cost == results[1].cost


def test_warm_start_from_rrt_connect_path() -> None:
    planned = plan_rrt_connect(
        START, GOAL, SPACE, WORLD, RrtConnectHyperparameters(step_size=0.2), seed=0
    ).require_path()
    result = optimize_trajectory(START, GOAL, SPACE, DISC_CLEARANCE, SETTINGS, initial_path=planned)
    assert result.success
    assert check_path_densely(result.waypoints, WORLD, 1e-3).collision_free


def test_goal_in_collision_fails() -> None:
    goal_in_disc = CENTER + np.array([0.1, 0.0])
    result = optimize_trajectory(START, goal_in_disc, SPACE, DISC_CLEARANCE, SETTINGS)
    assert not result.success
    assert result.solution_status == "goal in collision"


def test_a_goal_closer_than_the_margin_but_free_is_reached() -> None:
    goal_near_disc = CENTER + np.array([RADIUS + 0.5 * SETTINGS.collision_margin, 0.0])
    result = optimize_trajectory(START, goal_near_disc, SPACE, DISC_CLEARANCE, SETTINGS)
    assert result.success, result.solution_status
    np.testing.assert_allclose(result.waypoints[-1], goal_near_disc, atol=1e-9)
    interior = [disc_signed_distance(q)[0] for q in result.waypoints[1:-1]]
    assert min(interior) >= SETTINGS.collision_margin - 1e-6


def test_points_between_waypoints_keep_the_margin() -> None:
    coarse = TrajectoryOptimizationSettings(
        num_waypoints=8, max_step=0.3, collision_margin=0.02, samples_between_waypoints=3
    )
    result = optimize_trajectory(START, GOAL, SPACE, DISC_CLEARANCE, coarse)
    assert result.success, result.solution_status
    for a, b in zip(result.waypoints[:-1], result.waypoints[1:], strict=True):
        for fraction in (0.25, 0.5, 0.75):
            assert disc_signed_distance((1 - fraction) * a + fraction * b)[0] >= 0.02 - 1e-6


def test_unreachable_step_bound_is_rejected() -> None:
    tight = TrajectoryOptimizationSettings(num_waypoints=5, max_step=0.1)
    with pytest.raises(InvalidMotionQueryError, match="raise num_waypoints or max_step"):
        build_trajectory_program(START, GOAL, SPACE, DISC_CLEARANCE, tight)


def test_seven_joints_around_a_ball() -> None:
    space = ConfigurationSpace(np.full(7, -np.pi), np.full(7, np.pi))
    center = np.r_[0.0, 0.05, np.zeros(5)]

    def signed_distance(q: npt.NDArray[np.float64]) -> tuple[float, npt.NDArray[np.float64]]:
        offset = q - center
        distance = float(np.linalg.norm(offset))
        return distance - 0.8, offset / distance

    start, goal = np.r_[-1.5, np.zeros(6)], np.r_[1.5, np.zeros(6)]
    result = optimize_trajectory(start, goal, space, one_at_a_time(signed_distance))
    assert result.success and result.waypoints.shape == (50, 7)
    assert check_path_densely(result.waypoints, BoxBallWorld(balls=[(center, 0.8)]), 1e-3).collision_free
