from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

from kitchen_tamp.motion import (
    ConfigurationSpace,
    CountingSegmentChecker,
    MotionPlanner,
    RrtConnectHyperparameters,
    ShortcutHyperparameters,
    densify_path,
    path_length,
    plan_rrt,
    plan_rrt_connect,
    prune_waypoints,
    shortcut_path,
)
from kitchen_tamp.motion.sampling.shortcut import _piece_known_free, connect_furthest_vertices
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


@pytest.mark.parametrize("seed", [-1, 2**63])
def test_a_seed_outside_the_streams_is_refused(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld, seed: int
) -> None:
    raw = plan_rrt(START, GOAL, unit_square, wall_with_gap, seed=0).require_path()
    with pytest.raises(ValueError, match="seed must be a non-negative integer below 2"):
        shortcut_path(raw, wall_with_gap, seed=seed)


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


class RecordingWorld(BoxBallWorld):
    """A box-and-ball world that remembers every configuration it was asked about."""

    def __init__(self, world: BoxBallWorld) -> None:
        super().__init__(boxes=world.boxes, balls=world.balls)
        self.checked: list[npt.NDArray[np.float64]] = []

    def is_valid(self, qs: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
        self.checked.append(np.array(qs, dtype=np.float64))
        return super().is_valid(qs)


@pytest.mark.parametrize("planner", [plan_rrt, plan_rrt_connect])
@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_every_configuration_of_the_result_was_checked(
    unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld, seed: int, planner: MotionPlanner
) -> None:
    """The docstring's guarantee, white box: the points a dense check of the smoothed path visits
    were all checked while planning or smoothing (snapped waypoints need no new check)."""
    world = RecordingWorld(wall_with_gap)
    raw = planner(START, GOAL, unit_square, world, seed=seed).require_path()
    smoothed = shortcut_path(raw, world, seed=seed).path
    dense = densify_path(smoothed, ShortcutHyperparameters().edge_resolution)
    checked = np.concatenate(world.checked)
    distances = np.linalg.norm(dense[:, np.newaxis, :] - checked[np.newaxis, :, :], axis=2)
    assert np.all(distances.min(axis=1) < 1e-9)


def test_pieces_of_checked_segments_are_rechecked_only_when_rounding_moves_their_grid() -> None:
    """White box: a piece between grid configurations of a checked segment is free without a
    check, unless rounding gives it another interval count (here 1.3 = 13 resolutions)."""
    segments = CountingSegmentChecker(BoxBallWorld(), 0.1)
    q0, q1 = np.zeros(2), np.array([1.3, 0.0])
    assert _piece_known_free(segments, q0, q0 + (5 / 13) * (q1 - q0), 5)
    assert segments.configurations_checked == 0
    assert _piece_known_free(segments, q0, q0 + (3 / 13) * (q1 - q0), 3)
    assert segments.configurations_checked == 3  # checked in 4 intervals of its own


def test_random_shortcutting_stops_after_unsuccessful_tries(wall_with_gap: BoxBallWorld) -> None:
    straight = np.array([[0.1, 0.1], [0.2, 0.1], [0.3, 0.1]])  # no try can gain anything
    params = ShortcutHyperparameters(
        max_iterations=50, max_unsuccessful_tries=5, connect_furthest_vertices=False, prune_waypoints=False
    )
    assert shortcut_path(straight, wall_with_gap, params).iterations == 5
    patient = replace(params, max_unsuccessful_tries=None)
    assert shortcut_path(straight, wall_with_gap, patient).iterations == 50


def test_tries_that_cannot_gain_enough_cost_no_checks(wall_with_gap: BoxBallWorld) -> None:
    detour = np.array([[0.1, 0.1], [0.2, 0.3], [0.3, 0.1], [0.35, 0.25]])
    params = ShortcutHyperparameters(
        min_gain_per_length=1e9,
        connect_furthest_vertices=False,
        corner_cutting_passes=0,
        prune_waypoints=False,
    )
    result = shortcut_path(detour, wall_with_gap, params)
    np.testing.assert_array_equal(result.path, detour)
    assert result.collision_checks == 0 and result.shortcuts_taken == 0


def test_vertices_connect_to_the_furthest_one_in_sight(wall_with_gap: BoxBallWorld) -> None:
    zigzag = np.array([[0.1, 0.1], [0.2, 0.3], [0.3, 0.1], [0.4, 0.3], [0.5, 0.5], [0.6, 0.45], [0.9, 0.2]])
    checker = CountingSegmentChecker(wall_with_gap, 0.01)
    connected = connect_furthest_vertices(zigzag, checker)
    np.testing.assert_array_equal(connected, zigzag[[0, 4, 6]])  # through the gap
    assert path_length(connected) <= path_length(zigzag)


def test_same_seed_same_result_and_cost_in_seven_joints() -> None:
    space = ConfigurationSpace(np.full(7, -np.pi), np.full(7, np.pi))
    world = BoxBallWorld(balls=[([0.0] * 7, 0.8), ([0.0, 1.2, 0.0, 0.0, 0.0, 0.0, 0.0], 0.5)])
    start, goal = np.r_[-1.0, np.zeros(6)], np.r_[1.0, np.zeros(6)]
    raw = plan_rrt_connect(start, goal, space, world, RrtConnectHyperparameters(step_size=0.2), seed=3)
    first = shortcut_path(raw.require_path(), world, seed=7)
    second = shortcut_path(raw.require_path(), world, seed=7)
    np.testing.assert_array_equal(first.path, second.path)
    assert (first.iterations, first.shortcuts_taken, first.collision_checks) == (
        second.iterations,
        second.shortcuts_taken,
        second.collision_checks,
    )
    assert_valid_path(first.path, start, goal, world, space)


@pytest.mark.parametrize(
    ("field", "value"),
    [("max_unsuccessful_tries", 0), ("min_gain_per_length", -0.1), ("corner_cutting_passes", -1)],
)
def test_new_hyperparameters_are_validated(field: str, value: float) -> None:
    with pytest.raises(ValueError, match=field):
        changes: dict[str, Any] = {field: value}
        replace(ShortcutHyperparameters(), **changes)
