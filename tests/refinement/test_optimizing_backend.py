"""The trajectory-optimisation back end on a 2-D joint space with a disc obstacle."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pytest

from kitchen_tamp.motion import check_path_densely
from kitchen_tamp.refinement.optimizing_backend import OptimizingMotionBackend
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from tests.motion.toy_worlds import BoxBallWorld

CENTER, RADIUS = np.array([0.5, 0.5]), 0.15
DISC = BoxBallWorld(balls=[(CENTER, RADIUS)])
FloatArray = npt.NDArray[np.float64]


@dataclass
class DiscModel:
    """Joint limits, validity and signed distance of the disc world."""

    world: BoxBallWorld
    lower: FloatArray
    upper: FloatArray

    def is_valid(self, qs: FloatArray) -> npt.NDArray[np.bool_]:
        return self.world.is_valid(np.atleast_2d(qs))

    def segment_valid(self, q0: FloatArray, q1: FloatArray) -> bool:
        return self.world.segment_valid(q0, q1)

    def signed_distance(self, q: FloatArray) -> tuple[float, FloatArray]:
        offset = q - CENTER
        distance = float(np.linalg.norm(offset))
        return distance - RADIUS, offset / max(distance, 1e-12)


def model(world: BoxBallWorld = DISC) -> DiscModel:
    return DiscModel(world, np.zeros(2), np.ones(2))


def test_the_straight_line_through_the_disc_is_bent_around_it() -> None:
    start, goal = np.array([0.1, 0.52]), np.array([0.9, 0.5])
    checker = model()
    solution = OptimizingMotionBackend().solve(start, goal, checker, checker, np.random.default_rng(0))
    assert solution.solved and solution.path is not None
    assert np.allclose(solution.path[0], start) and np.allclose(solution.path[-1], goal)
    assert check_path_densely(solution.path, DISC, 1e-3).collision_free
    attempts = solution.figures["attempts"]
    # the straight line collides, so the optimiser starts from the RRT-Connect path
    assert isinstance(attempts, list) and str(attempts[0]["initial_guess"]).startswith("rrt_connect seed")
    assert attempts[0]["clearance"] == "drake"
    assert solution.figures["length_ratio_to_rrt_connect"] is not None
    assert solution.figures["waypoints"] == DEFAULT_SETTINGS.num_waypoints


def test_a_free_straight_line_is_the_initial_guess_and_the_answer() -> None:
    start, goal = np.array([0.1, 0.1]), np.array([0.9, 0.2])
    checker = model()
    solution = OptimizingMotionBackend().solve(start, goal, checker, checker, np.random.default_rng(0))
    assert solution.solved and solution.path is not None
    attempts = solution.figures["attempts"]
    assert isinstance(attempts, list) and attempts[0]["initial_guess"] == "straight line"
    expected = np.linspace(start, goal, DEFAULT_SETTINGS.num_waypoints)
    np.testing.assert_allclose(solution.path, expected, atol=1e-6)
    # nothing to warm-start from is needed: no RRT-Connect reference was planned
    assert solution.figures["rrt_connect_planned"] is False
    assert solution.figures["length_ratio_to_rrt_connect"] is None


def test_same_rng_gives_the_same_trajectory() -> None:
    start, goal = np.array([0.1, 0.52]), np.array([0.9, 0.5])
    checker = model()
    a = OptimizingMotionBackend().solve(start, goal, checker, checker, np.random.default_rng(3))
    b = OptimizingMotionBackend().solve(start, goal, checker, checker, np.random.default_rng(3))
    assert a.path is not None and b.path is not None and np.array_equal(a.path, b.path)


def test_an_unverifiable_result_is_never_accepted() -> None:
    start, goal = np.array([0.1, 0.52]), np.array([0.9, 0.5])
    planning = model()
    wall = model(BoxBallWorld(balls=[(CENTER, RADIUS)], boxes=[((0.45, 0.0), (0.55, 1.0))]))
    solution = OptimizingMotionBackend().solve(start, goal, planning, wall, np.random.default_rng(0))
    assert not solution.solved and solution.path is None
    assert all(a.get("dense_check") != "free" for a in solution.figures["attempts"])  # type: ignore[union-attr]
    assert solution.figures["rrt_connect_path_length_rad"] is None  # no warm start to try either


def test_a_checker_without_signed_distance_is_refused() -> None:
    class NoDistance:
        lower, upper = np.zeros(2), np.ones(2)

        def is_valid(self, qs: FloatArray) -> npt.NDArray[np.bool_]:
            return np.ones(len(np.atleast_2d(qs)), dtype=bool)

        def segment_valid(self, q0: FloatArray, q1: FloatArray) -> bool:
            return True

    with pytest.raises(ValueError, match="signed distances"):
        OptimizingMotionBackend().solve(
            np.zeros(2), np.ones(2), NoDistance(), NoDistance(), np.random.default_rng(0)
        )
