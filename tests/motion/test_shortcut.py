from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.motion import (
    ConfigurationSpace,
    CountingSegmentChecker,
    RrtConnectHyperparameters,
    ShortcutHyperparameters,
    path_length,
    plan_rrt,
    plan_rrt_connect,
    prune_waypoints,
    shortcut_path,
)
from tests.motion.toy_worlds import BoxBallWorld, assert_valid_path

START = np.array([0.1, 0.1])
GOAL = np.array([0.9, 0.2])


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_shortcut_of_rrt_path_is_valid_and_not_longer(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld, seed: int
) -> None:
    raw = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=seed).require_path()
    result = shortcut_path(raw, wall_with_gap, seed=seed)
    assert_valid_path(result.path, START, GOAL, wall_with_gap, unit_square)
    assert path_length(result.path) <= path_length(raw)
    assert len(result.path) <= len(raw)
    assert result.shortcuts_taken > 0 and result.collision_checks > 0


def test_shortcut_gets_close_to_the_shortest_path_through_the_gap(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld
) -> None:
    raw = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=0).require_path()
    smoothed = shortcut_path(raw, wall_with_gap, seed=0).path
    shortest = np.linalg.norm([0.45, 0.4] - START) + np.linalg.norm(GOAL - [0.55, 0.4]) + 0.1
    assert path_length(smoothed) < 1.1 * shortest


def test_same_seed_same_result(unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld) -> None:
    raw = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=0).require_path()
    first = shortcut_path(raw, wall_with_gap, seed=11).path
    second = shortcut_path(raw, wall_with_gap, seed=11).path
    np.testing.assert_array_equal(first, second)


def test_zero_iterations_only_prunes(wall_with_gap: BoxBallWorld) -> None:
    collinear = np.array([[0.1, 0.1], [0.2, 0.1], [0.3, 0.1], [0.4, 0.45], [0.6, 0.45]])
    params = ShortcutHyperparameters(max_iterations=0, corner_cutting_passes=0)
    result = shortcut_path(collinear, wall_with_gap, params)
    np.testing.assert_array_equal(result.path, collinear[[0, 3, 4]])
    assert result.iterations == 0


def test_prune_keeps_needed_corners(wall_with_gap: BoxBallWorld) -> None:
    around_wall = np.array([[0.3, 0.2], [0.4, 0.5], [0.6, 0.5], [0.7, 0.2]])
    checker = CountingSegmentChecker(wall_with_gap, 0.01)
    np.testing.assert_array_equal(prune_waypoints(around_wall, checker), around_wall)


def test_two_waypoint_path_is_returned_unchanged(wall_with_gap: BoxBallWorld) -> None:
    path = np.array([START, [0.3, 0.1]])
    np.testing.assert_array_equal(shortcut_path(path, wall_with_gap).path, path)


def test_seven_joint_path_is_shortened() -> None:
    space = ConfigurationSpace(np.full(7, -np.pi), np.full(7, np.pi))
    world = BoxBallWorld(balls=[(np.zeros(7), 0.8)])
    start, goal = np.r_[-1.0, np.zeros(6)], np.r_[1.0, np.zeros(6)]
    params = RrtConnectHyperparameters(step_size=0.2)
    raw = plan_rrt_connect(start, goal, space, world, params, seed=0).require_path()
    smoothed = shortcut_path(raw, world, seed=0).path
    assert_valid_path(smoothed, start, goal, world, space)
    assert path_length(smoothed) < path_length(raw)


def test_hyperparameters_are_validated() -> None:
    with pytest.raises(ValueError, match="max_iterations"):
        ShortcutHyperparameters(max_iterations=-1)
