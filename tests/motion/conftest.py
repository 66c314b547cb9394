"""Fixtures for motion-planning tests: the unit square, small obstacle worlds, and the kitchen
(built only for the tests that compare a planning-time geometry model with PyBullet)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from kitchen_tamp.kitchen import KitchenScene, load_kitchen_problem
from kitchen_tamp.motion import ConfigurationSpace
from tests.kitchen.conftest import REPO
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


@pytest.fixture(scope="module")
def kitchen() -> Iterator[KitchenScene]:
    """The kitchen of ``problem.pddl``, one per test module."""
    _, built = load_kitchen_problem(REPO / "pddl" / "problem.pddl")
    with built:
        yield built
