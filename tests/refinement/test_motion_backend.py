"""The sampling motion back end on small 2-D joint spaces: paths found and re-checked,
blocked queries fail within their budget, the same RNG gives the same path."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from kitchen_tamp.motion import MOTION_PLANNERS, RrtConnectHyperparameters, check_path_densely
from kitchen_tamp.refinement import SamplingMotionBackend
from tests.motion.toy_worlds import WALL_WITH_GAP, BoxBallWorld


@dataclass
class Bounded:
    """A toy world with joint limits, as the back end expects of a checker."""

    world: BoxBallWorld
    lower: np.ndarray
    upper: np.ndarray

    def is_valid(self, qs: np.ndarray) -> np.ndarray:
        return self.world.is_valid(np.atleast_2d(qs))

    def segment_valid(self, q0: np.ndarray, q1: np.ndarray) -> bool:
        return self.world.segment_valid(q0, q1)


def bounded(world: BoxBallWorld) -> Bounded:
    return Bounded(world, np.zeros(2), np.ones(2))


START, GOAL = np.array([0.1, 0.5]), np.array([0.9, 0.5])


@pytest.mark.parametrize("planner", sorted(MOTION_PLANNERS))
def test_finds_a_path_through_the_gap_that_passes_the_dense_check(planner: str) -> None:
    checker = bounded(WALL_WITH_GAP)
    solution = SamplingMotionBackend(planner=planner).solve(
        START, GOAL, checker, checker, np.random.default_rng(0)
    )
    assert solution.solved and solution.path is not None
    assert np.allclose(solution.path[0], START) and np.allclose(solution.path[-1], GOAL)
    assert check_path_densely(solution.path, WALL_WITH_GAP, 0.001).collision_free
    assert solution.figures["waypoints"] == len(solution.path)
    assert float(solution.figures["path_length_rad"]) <= float(solution.figures["raw_path_length_rad"]) + 1e-9


def test_same_rng_seed_gives_the_same_path() -> None:
    checker = bounded(WALL_WITH_GAP)
    backend = SamplingMotionBackend()
    a = backend.solve(START, GOAL, checker, checker, np.random.default_rng(7))
    b = backend.solve(START, GOAL, checker, checker, np.random.default_rng(7))
    assert a.path is not None and b.path is not None
    assert np.array_equal(a.path, b.path) and a.figures == b.figures


def test_blocked_query_fails_within_its_attempts() -> None:
    wall = BoxBallWorld(boxes=[((0.45, 0.0), (0.55, 1.0))])
    checker = bounded(wall)
    backend = SamplingMotionBackend(attempts=2, hyperparameters=RrtConnectHyperparameters(max_iterations=200))
    solution = backend.solve(START, GOAL, checker, checker, np.random.default_rng(0))
    assert not solution.solved and solution.path is None
    assert solution.attempts == 2
    assert solution.status == "iteration limit reached"
    assert solution.figures["iterations"] == 400


def test_a_path_free_for_the_planner_but_not_for_the_strict_checker_is_rejected() -> None:
    thin_wall = BoxBallWorld(boxes=[((0.4995, 0.0), (0.5005, 1.0))])  # thinner than the edge checks
    planner_view = bounded(BoxBallWorld())
    strict = bounded(thin_wall)
    solution = SamplingMotionBackend(attempts=2).solve(
        START, GOAL, planner_view, strict, np.random.default_rng(0)
    )
    assert not solution.solved
    assert solution.figures["dense_check_failures"] == 2


def test_rejects_unknown_planner_names() -> None:
    with pytest.raises(ValueError, match="unknown motion planner 'prm'; choose one of rrt, rrt_connect"):
        SamplingMotionBackend(planner="prm")
