"""Fixtures for motion-planning tests: the unit square and small obstacle worlds."""

from __future__ import annotations

import pytest

from kitchen_tamp.motion import ConfigurationSpace
from tests.motion.toy_worlds import (
    ENCLOSED_GOAL_WORLD,
    UNIT_SQUARE,
    WALL_WITH_GAP,
    BoxBallWorld,
)


@pytest.fixture
def unit_square() -> ConfigurationSpace:
    return UNIT_SQUARE


@pytest.fixture
def wall_with_gap() -> BoxBallWorld:
    return BoxBallWorld(boxes=WALL_WITH_GAP.boxes, balls=WALL_WITH_GAP.balls)


@pytest.fixture
def enclosed_goal_world() -> BoxBallWorld:
    return BoxBallWorld(boxes=ENCLOSED_GOAL_WORLD.boxes)
