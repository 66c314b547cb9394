from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.motion import (
    ConfigurationSpace,
    InvalidMotionQueryError,
    MotionPlanningError,
    PlanStatus,
    RrtHyperparameters,
    plan_rrt,
)
from tests.motion.toy_worlds import BoxBallWorld, assert_valid_path

START = np.array([0.1, 0.1])
GOAL = np.array([0.9, 0.2])  # the straight line from START hits the wall


def test_finds_valid_path_through_gap(
    unit_square: ConfigurationSpace,
    wall_with_gap: BoxBallWorld,
) -> None:
    result = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=1)
    assert result.status is PlanStatus.SOLVED
    assert_valid_path(result.path, START, GOAL, wall_with_gap, unit_square)
    assert result.collision_checks > 0 and result.nodes >= len(result.require_path())


def test_same_seed_same_path(unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld) -> None:
    first = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=7).require_path()
    second = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=7).require_path()
    other = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=8).require_path()
    np.testing.assert_array_equal(first, second)
    assert first.shape != other.shape or not np.array_equal(first, other)


def test_enclosed_goal_fails_with_iteration_limit(
    unit_square: ConfigurationSpace, enclosed_goal_world: BoxBallWorld
) -> None:
    params = RrtHyperparameters(max_iterations=500)
    result = plan_rrt(START, [0.85, 0.85], unit_square, enclosed_goal_world, params, seed=0)
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.path is None
    assert result.iterations == 500 and result.nodes > 1 and result.collision_checks > 0
    with pytest.raises(MotionPlanningError, match="iteration limit"):
        result.require_path()


def test_exhausted_time_budget_is_reported(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld
) -> None:
    result = plan_rrt(START, GOAL, unit_square, wall_with_gap, time_budget_s=0.0)
    assert result.status is PlanStatus.TIME_LIMIT
    assert result.iterations == 0


@pytest.mark.parametrize(
    ("start", "goal", "status"),
    [
        ([0.5, 0.2], GOAL, PlanStatus.START_IN_COLLISION),
        (START, [0.5, 0.8], PlanStatus.GOAL_IN_COLLISION),
    ],
)
def test_endpoint_in_collision_is_named(
    unit_square: ConfigurationSpace,
    wall_with_gap: BoxBallWorld,
    start: list[float],
    goal: list[float],
    status: PlanStatus,
) -> None:
    result = plan_rrt(start, goal, unit_square, wall_with_gap)
    assert result.status is status
    assert result.iterations == 0 and result.collision_checks == 2


@pytest.mark.parametrize(
    ("start", "message"),
    [([0.1, 0.1, 0.1], "start must have shape"), ([1.5, 0.1], "outside the joint bounds")],
)
def test_malformed_start_raises(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld, start: list[float], message: str
) -> None:
    with pytest.raises(InvalidMotionQueryError, match=message):
        plan_rrt(start, GOAL, unit_square, wall_with_gap)


def test_hyperparameters_are_validated() -> None:
    with pytest.raises(ValueError, match="goal_bias"):
        RrtHyperparameters(goal_bias=1.5)
    with pytest.raises(ValueError, match="step_size"):
        RrtHyperparameters(step_size=0.0)


def test_defaults_match_the_class_project() -> None:
    params = RrtHyperparameters()
    assert params.goal_bias == 0.2
    assert params.step_size == pytest.approx(np.deg2rad(5.0))
    assert params.edge_resolution == 0.01
    assert params.goal_tolerance == pytest.approx(np.deg2rad(1.0))
    assert params.max_iterations == 10_000
