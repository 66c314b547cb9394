"""Tiny joint-space worlds for motion-planning tests: boxes and balls, checked in numpy."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion import (
    ConfigurationSpace,
    CountingSegmentChecker,
    check_path_densely,
    densify_path,
)

FINE_RESOLUTION = 1e-3
"""Resolution at which tests re-check whole paths, ten times finer than the planners'."""

PLANNER_RESOLUTION = 0.01
"""Edge-check resolution of the planners' defaults: a segment checked at this
spacing may cut an obstacle's corner or rim by up to half of it between two
checked configurations, so paths are re-checked against obstacles shrunk by that."""


@dataclass
class BoxBallWorld:
    """Axis-aligned boxes and balls as obstacles in joint space (any dimension)."""

    boxes: Sequence[tuple[Sequence[float], Sequence[float]]] = ()
    balls: Sequence[tuple[Sequence[float], float]] = ()
    calls: int = field(default=0, init=False)

    def is_valid(self, qs: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
        self.calls += 1
        valid = np.ones(len(qs), dtype=np.bool_)
        for lower, upper in self.boxes:
            valid &= ~np.all((qs >= lower) & (qs <= upper), axis=1)
        for center, radius in self.balls:
            valid &= np.linalg.norm(qs - np.asarray(center), axis=1) > radius
        return valid

    def segment_valid(self, q0: npt.NDArray[np.float64], q1: npt.NDArray[np.float64]) -> bool:
        return CountingSegmentChecker(self, FINE_RESOLUTION).segment_valid(q0, q1)

    def shrunk(self, margin: float) -> BoxBallWorld:
        """The same world with every obstacle shrunk by `margin` on each side."""
        return BoxBallWorld(
            boxes=[(np.add(lo, margin), np.subtract(hi, margin)) for lo, hi in self.boxes],
            balls=[(center, radius - margin) for center, radius in self.balls],
        )


UNIT_SQUARE = ConfigurationSpace(np.zeros(2), np.ones(2))

WALL_WITH_GAP = BoxBallWorld(
    boxes=[((0.45, 0.0), (0.55, 0.4)), ((0.45, 0.6), (0.55, 1.0))],
    balls=[((0.25, 0.5), 0.1)],
)
"""A vertical wall across the unit square with a gap at 0.4 < y < 0.6, and a disc."""

ENCLOSED_GOAL_WORLD = BoxBallWorld(
    boxes=[
        ((0.7, 0.7), (1.0, 0.75)),
        ((0.7, 0.7), (0.75, 1.0)),
        ((0.7, 0.95), (1.0, 1.0)),
        ((0.95, 0.7), (1.0, 1.0)),
    ]
)
"""A closed square frame around (0.85, 0.85)."""


def assert_valid_path(
    path: npt.NDArray[np.float64] | None,
    start: npt.ArrayLike,
    goal: npt.ArrayLike,
    world: BoxBallWorld,
    space: ConfigurationSpace,
) -> None:
    assert path is not None
    assert path.ndim == 2 and path.shape[1] == space.dimension
    np.testing.assert_array_equal(path[0], start)
    np.testing.assert_array_equal(path[-1], goal)
    assert np.all(path >= space.lower) and np.all(path <= space.upper)
    assert check_path_densely(path, world, PLANNER_RESOLUTION).collision_free
    dense = densify_path(path, FINE_RESOLUTION)
    assert np.all(world.shrunk(PLANNER_RESOLUTION / 2).is_valid(dense))
