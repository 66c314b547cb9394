"""Configuration space, tree, segment checks, joint paths, verification and the registry."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.joint_spacing import coarse_to_fine_order
from kitchen_tamp.motion import (
    MOTION_PLANNERS,
    ConfigurationSpace,
    CountingSegmentChecker,
    InvalidMotionQueryError,
    UnknownPlannerError,
    check_path_densely,
    densify_path,
    path_length,
    plan_rrt,
    plan_rrt_connect,
    planner_named,
    planner_options,
    resample_path,
)
from kitchen_tamp.motion.sampling.configuration_tree import ConfigurationTree
from kitchen_tamp.motion.segment_checking import raked_order
from tests.motion.toy_worlds import BoxBallWorld

WALL = BoxBallWorld(boxes=[((0.45, 0.0), (0.55, 1.0))])


def test_space_rejects_inverted_bounds() -> None:
    with pytest.raises(ValueError, match="joints \\[1\\]"):
        ConfigurationSpace(np.zeros(2), np.array([1.0, 0.0]))


def test_space_validates_configurations() -> None:
    space = ConfigurationSpace(np.zeros(2), np.ones(2))
    np.testing.assert_array_equal(space.validated([0.5, 1.0], "goal"), [0.5, 1.0])
    with pytest.raises(InvalidMotionQueryError, match="goal is not finite"):
        space.validated([np.nan, 0.5], "goal")
    with pytest.raises(InvalidMotionQueryError, match="start is outside the joint bounds at joints \\[1\\]"):
        space.validated([0.5, 1.5], "start")
    with pytest.raises(InvalidMotionQueryError, match="shape \\(2,\\)"):
        space.validated([0.5, 0.5, 0.5], "start")


def test_uniform_samples_are_numpys_uniform_draws() -> None:
    """`sample_uniform` scales standard uniforms itself (a third of ``rng.uniform``'s time with
    array bounds): the same values, so the same seed plans the same."""
    space = ConfigurationSpace(np.array([-2.9, -1.8, 0.0]), np.array([2.9, 1.8, 3.75]))
    for seed in range(5):
        ours = space.sample_uniform(np.random.default_rng(seed), 64)
        numpys = np.random.default_rng(seed).uniform(space.lower, space.upper, size=(64, 3))
        np.testing.assert_array_equal(ours, numpys)


def test_tree_grows_past_its_capacity_and_finds_nearest() -> None:
    tree = ConfigurationTree(np.zeros(2), initial_capacity=2)
    parent = 0
    for step in range(1, 10):
        parent = tree.add(np.array([step, 0.0]), parent)
    assert len(tree) == 10
    assert tree.nearest(np.array([6.2, 3.0])) == 6
    np.testing.assert_array_equal(tree.path_from_root(3)[:, 0], [0, 1, 2, 3])
    assert not tree.nodes.flags.writeable


def test_coarse_to_fine_order_is_a_permutation_starting_in_the_middle() -> None:
    order = coarse_to_fine_order(7)
    assert sorted(order.tolist()) == list(range(7))
    assert order[0] == 3 and set(order[1:3].tolist()) == {1, 5}


def test_segment_check_counts_and_fails_fast_at_endpoints() -> None:
    checker = CountingSegmentChecker(WALL, 0.01)
    assert not checker.segment_valid(np.array([0.5, 0.5]), np.array([0.9, 0.5]))
    assert checker.configurations_checked == 2
    assert checker.segment_valid(np.array([0.1, 0.5]), np.array([0.2, 0.5]))
    assert checker.configurations_checked == 2 + 2 + 9


def test_free_prefix_stops_before_the_wall_on_resolution_multiples() -> None:
    checker = CountingSegmentChecker(WALL, 0.01)
    free = checker.free_prefix_length(np.array([0.0, 0.5]), np.array([1.0, 0.5]))
    assert free == pytest.approx(0.44)  # the last free point before x = 0.45
    assert checker.configurations_checked == 16 + 32  # batches of 16, 32 reach x = 0.45
    assert checker.free_prefix_length(np.array([0.0, 0.5]), np.array([0.3, 0.5])) == 0.3


def test_a_raked_free_prefix_visits_each_block_end_first_and_stops_on_whole_blocks() -> None:
    order = raked_order(23, 10)
    assert sorted(order) == list(range(23))
    assert list(order[:3]) == [9, 7, 3] and list(order[10:12]) == [19, 17]  # ends first, then coarse to fine
    assert list(order[20:]) == [22, 21, 20]  # a last, shorter block
    checker = CountingSegmentChecker(WALL, 0.01)
    q0, q1 = np.array([0.0, 0.5]), np.array([1.0, 0.5])
    assert checker.free_prefix_length(q0, q1, 20) == pytest.approx(0.40)  # blocks end at 0.2, 0.4, 0.6
    assert checker.configurations_checked == 16 + 32  # the third block's third point (x = 0.48), second batch
    assert checker.free_prefix_length(q0, q1, 45) == 0.0  # the wall at x = 0.45 is in the first block
    assert checker.free_prefix_length(q0, np.array([0.3, 0.5]), 20) == 0.3


def test_resample_and_densify_keep_endpoints_and_length() -> None:
    path = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    resampled = resample_path(path, 5)
    np.testing.assert_allclose(resampled, [[0, 0], [0.5, 0], [1, 0], [1, 0.5], [1, 1]])
    dense = densify_path(path, 0.1)
    assert len(dense) == 21 and path_length(dense) == pytest.approx(2.0)
    assert np.max(np.linalg.norm(np.diff(dense, axis=0), axis=1)) <= 0.1 + 1e-12


def test_dense_check_names_the_colliding_segment() -> None:
    path = np.array([[0.1, 0.5], [0.3, 0.5], [0.3, 0.2], [0.9, 0.2]])
    check = check_path_densely(path, WALL, 0.01)
    assert not check.collision_free and check.first_colliding_segment == 2
    assert check_path_densely(path[:3], WALL, 0.01).collision_free


def test_registry_names_planners_for_the_cli() -> None:
    assert {name: entry.plan for name, entry in MOTION_PLANNERS.items()} == {
        "rrt": plan_rrt, "rrt_connect": plan_rrt_connect}
    assert planner_named("rrt_connect") is plan_rrt_connect
    assert planner_options() == {"connect": "rrt_connect", "basic": "rrt"}
    with pytest.raises(UnknownPlannerError, match="choose one of rrt, rrt_connect"):
        planner_named("prm")


@pytest.mark.parametrize("name", sorted(MOTION_PLANNERS))
def test_every_registered_planner_solves_the_wall_with_gap(
    name: str, unit_square: ConfigurationSpace, wall_with_gap: BoxBallWorld
) -> None:
    result = planner_named(name)([0.1, 0.1], [0.9, 0.2], unit_square, wall_with_gap, seed=0)
    assert result.solved
