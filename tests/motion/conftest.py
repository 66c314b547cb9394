"""Fixtures for motion-planning tests: the unit square, small obstacle worlds, and the kitchen
(built only for the tests that compare a planning-time geometry model with PyBullet), with the
pair of checkers such a comparison needs: PyBullet's and its twin in the model under test."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Generic, TypeVar

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene, load_kitchen_problem, sample_targets
from kitchen_tamp.motion import ConfigurationSpace
from kitchen_tamp.world import PyBulletCollisionChecker
from kitchen_tamp.world.scene_description import describe_collision_checker
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
def mbm_table(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Any, Any, Any]]:
    """MotionBenchMaker's table_pick problem 7 (written out in `test_motion_bench_maker`), with its
    sphere model and Drake's model (imported here, so that other tests do not load Drake)."""
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
    from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
    from kitchen_tamp.motion.motion_bench_maker import mbm_scene, read_mbm_problem
    from kitchen_tamp.world import panda_urdf_path
    from tests.motion.test_motion_bench_maker import TABLE_REQUEST, TABLE_SCENE

    problem = read_mbm_problem("table_pick", 7, TABLE_SCENE, TABLE_REQUEST)
    scene = mbm_scene(problem, panda_urdf_path(), Path(tmp_path_factory.mktemp("table")))
    yield problem, SphereCollisionChecker(scene), DrakeCollisionChecker(scene)


@pytest.fixture(scope="module")
def kitchen() -> Iterator[KitchenScene]:
    """The kitchen of ``problem.pddl``, one per test module."""
    _, built = load_kitchen_problem(REPO / "pddl" / "problem.pddl")
    with built:
        yield built


Model = TypeVar("Model")


@dataclass(frozen=True, eq=False)
class CheckerPair(Generic[Model]):
    """PyBullet's checker of a kitchen state and the planning-time model of the same state."""

    pybullet: PyBulletCollisionChecker
    model: Model


def twin(checker: PyBulletCollisionChecker, model: Callable[..., Model]) -> Model:
    """The same scene for the other model, described from the files the simulator loaded."""
    return model(describe_collision_checker(checker), margin=checker.margin)


def free_hand_pair(kitchen: KitchenScene, model: Callable[..., Model]) -> CheckerPair[Model]:
    """The kitchen as it starts, the hand empty."""
    checker = kitchen.collision_checker()
    return CheckerPair(checker, twin(checker, model))


def holding_spam_pair(kitchen: KitchenScene, model: Callable[..., Model]) -> CheckerPair[Model]:
    """The hand holds the spam box as the pick skill grasped it (the kitchen is restored after)."""
    with kitchen.scene.preserved():
        sample_targets(kitchen, "pickUp", ("spam", "countertop"), np.random.default_rng(0)).apply(kitchen)
        assert kitchen.held_box() == "spam"
        checker = kitchen.collision_checker()
    return CheckerPair(checker, twin(checker, model))
