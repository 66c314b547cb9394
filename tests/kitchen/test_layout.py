from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import (
    InitialStateMismatchError,
    KitchenScene,
    UnknownObjectError,
    UnsupportedInitialStateError,
    abstract_state,
    build_kitchen,
)
from kitchen_tamp.kitchen.scene.regions import box_corners
from tests.kitchen.conftest import LAYOUT_PROBLEMS, PROBLEMS, task_of

OBJECTS = {"stove": "surface", "countertop": "surface", "drawer": "openable", "sugar": "box", "spam": "box"}


@pytest.mark.parametrize("problem", LAYOUT_PROBLEMS, ids=lambda p: p.stem)
def test_abstraction_of_the_built_scene_is_the_init(
    build: Callable[[Path], KitchenScene], problem: Path
) -> None:
    kitchen = build(problem)
    assert abstract_state(kitchen, task_of(problem).objects) == task_of(problem).init_atoms


@pytest.mark.parametrize("problem", LAYOUT_PROBLEMS, ids=lambda p: p.stem)
def test_boxes_rest_without_collision(build: Callable[[Path], KitchenScene], problem: Path) -> None:
    kitchen = build(problem)
    checker = kitchen.collision_checker()
    assert checker.is_valid(kitchen.home)[0]
    assert checker.min_clearance(kitchen.home)[0] > 0.0
    for name in kitchen.boxes:
        body = kitchen.box(name)
        bottom = float(np.min(box_corners(body.base_pose(), kitchen.box_size(name))[:, 2]))
        assert bottom > 0.3
        for other in kitchen.scene.bodies:
            if other is not body:
                assert not kitchen_contacts(kitchen, body.uid, other.uid)


def kitchen_contacts(kitchen: KitchenScene, a: int, b: int) -> bool:
    import pybullet as p

    points = p.getClosestPoints(a, b, 0.0, physicsClientId=kitchen.scene.client)
    return any(pt[8] < 0.0 for pt in points)


def test_unknown_object_is_named(build: Callable[[Path], KitchenScene]) -> None:
    with pytest.raises(UnknownObjectError, match="soup") as raised:
        build(PROBLEMS / "unknown_object.pddl")
    assert raised.value.name == "soup"


def test_wrongly_typed_object_is_rejected() -> None:
    objects = dict(OBJECTS, stove="box")
    with pytest.raises(UnknownObjectError, match="stove"):
        build_kitchen(objects, {("boxOn", "sugar", "countertop"), ("armClear",)})


def test_mismatched_init_names_the_atom(build: Callable[[Path], KitchenScene]) -> None:
    with pytest.raises(InitialStateMismatchError, match=r"\(surfClear countertop\)") as raised:
        build(PROBLEMS / "mismatched_init.pddl")
    assert raised.value.unexpected == ["(surfClear countertop)"]


def test_holding_at_start_is_rejected_clearly() -> None:
    init = {
        ("holding", "sugar"),
        ("boxOn", "spam", "stove"),
        ("surfClear", "countertop"),
        ("cabClear", "drawer"),
    }
    with pytest.raises(UnsupportedInitialStateError, match="holding sugar"):
        build_kitchen(OBJECTS, init)


def test_box_without_a_place_is_rejected() -> None:
    init = {("boxOn", "spam", "stove"), ("armClear",)}
    with pytest.raises(UnsupportedInitialStateError, match="sugar"):
        build_kitchen(OBJECTS, init)


def test_both_boxes_in_the_open_drawer() -> None:
    init = {
        ("boxIn", "sugar", "drawer"),
        ("boxIn", "spam", "drawer"),
        ("opened", "drawer"),
        ("surfClear", "stove"),
        ("surfClear", "countertop"),
        ("armClear",),
    }
    with build_kitchen(OBJECTS, init) as kitchen:
        assert abstract_state(kitchen) == frozenset(init)


def test_boxes_ride_with_the_drawer(build: Callable[[Path], KitchenScene]) -> None:
    kitchen = build(PROBLEMS / "sugar_in_closed_drawer.pddl")
    before = kitchen.box("sugar").base_pose().translation
    kitchen.set_opening("drawer", kitchen.opening_limits("drawer")[1])
    assert np.linalg.norm(kitchen.box("sugar").base_pose().translation - before) > 0.2
    assert ("boxIn", "sugar", "drawer") in abstract_state(kitchen)
    assert ("opened", "drawer") in abstract_state(kitchen)
