from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.motion import (
    ConfigurationSpace,
    PlanStatus,
    RrtConnectHyperparameters,
    path_length,
    plan_rrt_connect,
    shortcut_path,
)
from tests.motion.toy_worlds import BoxBallWorld, assert_valid_path

START = np.array([0.1, 0.1])
GOAL = np.array([0.9, 0.2])  # the straight line from START hits the wall


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_finds_valid_path_through_gap(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld, seed: int
) -> None:
    assert not wall_with_gap.segment_valid(START, GOAL)
    params = RrtConnectHyperparameters(step_size=0.1)
    result = plan_rrt_connect(START, GOAL, unit_square, wall_with_gap, params, seed=seed)
    assert result.status is PlanStatus.SOLVED
    assert_valid_path(result.path, START, GOAL, wall_with_gap, unit_square)


def test_free_straight_line_is_returned_directly(unit_square: ConfigurationSpace) -> None:
    result = plan_rrt_connect(START, GOAL, unit_square, BoxBallWorld())
    np.testing.assert_array_equal(result.require_path(), [START, GOAL])
    assert result.iterations == 0


def test_same_seed_same_path(unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld) -> None:
    paths = [
        plan_rrt_connect(START, GOAL, unit_square, wall_with_gap, seed=seed).require_path()
        for seed in (3, 3, 4)
    ]
    np.testing.assert_array_equal(paths[0], paths[1])
    assert paths[0].shape != paths[2].shape or not np.array_equal(paths[0], paths[2])


@pytest.mark.parametrize("seed", [-1, 2**63])
def test_a_seed_outside_the_streams_is_refused(unit_square: ConfigurationSpace, seed: int) -> None:
    with pytest.raises(ValueError, match="seed must be a non-negative integer below 2"):
        plan_rrt_connect(START, GOAL, unit_square, BoxBallWorld(), seed=seed)


def test_enclosed_goal_fails_with_iteration_limit(
    unit_square: ConfigurationSpace, enclosed_goal_world: BoxBallWorld
) -> None:
    params = RrtConnectHyperparameters(max_iterations=300)
    goal = [0.85, 0.85]
    result = plan_rrt_connect(START, goal, unit_square, enclosed_goal_world, params)
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.path is None and result.iterations == 300 and result.nodes > 2


def test_time_budget_stops_a_hopeless_search(
    unit_square: ConfigurationSpace, enclosed_goal_world: BoxBallWorld
) -> None:
    params = RrtConnectHyperparameters(max_iterations=10**9)
    goal = [0.85, 0.85]
    result = plan_rrt_connect(START, goal, unit_square, enclosed_goal_world, params, time_budget_s=0.05)
    assert result.status is PlanStatus.TIME_LIMIT
    assert 0 < result.iterations < params.max_iterations


@pytest.mark.parametrize(
    ("start", "goal", "status"),
    [
        ([0.5, 0.2], GOAL, PlanStatus.START_IN_COLLISION),
        (START, [0.25, 0.5], PlanStatus.GOAL_IN_COLLISION),
    ],
)
def test_endpoint_in_collision_is_named(
    unit_square: ConfigurationSpace,
    wall_with_gap: BoxBallWorld,
    start: list[float],
    goal: list[float],
    status: PlanStatus,
) -> None:
    assert plan_rrt_connect(start, goal, unit_square, wall_with_gap).status is status


def test_seven_joints_around_a_ball_then_shortcut() -> None:
    space = ConfigurationSpace(np.full(7, -np.pi), np.full(7, np.pi))
    slab_lower, slab_upper = np.full(7, -4.0), np.full(7, 4.0)
    slab_lower[0], slab_upper[0], slab_upper[2] = -0.2, 0.2, 0.0
    world = BoxBallWorld(balls=[(np.zeros(7), 1.5)], boxes=[(slab_lower, slab_upper)])
    start, goal = np.r_[-2.0, np.zeros(6)], np.r_[2.0, np.zeros(6)]
    assert not world.segment_valid(start, goal)
    result = plan_rrt_connect(start, goal, space, world, seed=5)
    assert result.status is PlanStatus.SOLVED
    assert_valid_path(result.path, start, goal, world, space)
    smoothed = shortcut_path(result.require_path(), world, seed=5).path
    assert_valid_path(smoothed, start, goal, world, space)
    assert path_length(smoothed) <= path_length(result.require_path())


def test_a_balanced_search_waits_for_a_tree_trapped_near_its_end(
    unit_square: ConfigurationSpace, enclosed_goal_world: BoxBallWorld
) -> None:
    goal = [0.85, 0.85]
    nodes = {}
    for tree_balance in (0.0, 1.5):
        params = RrtConnectHyperparameters(max_iterations=300, tree_balance=tree_balance)
        result = plan_rrt_connect(START, goal, unit_square, enclosed_goal_world, params)
        assert result.status is PlanStatus.ITERATION_LIMIT
        nodes[tree_balance] = result.nodes
    assert nodes[1.5] < nodes[0.0] / 2  # the start tree no longer outgrows the enclosed goal's


def test_a_tree_balance_below_one_is_refused() -> None:
    with pytest.raises(ValueError, match="tree_balance"):
        RrtConnectHyperparameters(tree_balance=0.5)
