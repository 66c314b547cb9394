"""Each skill on each kitchen object: targets are IK-verified and collision-free, and
applying them changes Ψ exactly as the action's effects say."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import (
    KitchenScene,
    SkillFailure,
    SkillTargets,
    UnknownActionError,
    UnknownObjectError,
    abstract_state,
    build_kitchen,
    sample_targets,
)
from kitchen_tamp.planning import Atom
from tests.kitchen.conftest import REPO

OBJECTS = {"stove": "surface", "countertop": "surface", "drawer": "openable", "sugar": "box", "spam": "box"}
OPEN_DRAWER_INIT: frozenset[Atom] = frozenset(
    {
        ("boxOn", "sugar", "stove"),
        ("boxOn", "spam", "countertop"),
        ("opened", "drawer"),
        ("cabClear", "drawer"),
        ("armClear",),
    }
)


def check_targets(kitchen: KitchenScene, targets: SkillTargets) -> None:
    """Goal valid for the free-space checker, segments chained and joint-continuous."""
    assert targets.free_space_checker.is_valid(targets.goal_configuration)[0]
    assert kitchen.robot.within_limits(targets.goal_configuration)
    for segment in targets.segments:
        assert segment.configurations.shape[1] == kitchen.robot.dof
        assert np.max(np.abs(np.diff(segment.configurations, axis=0))) <= 0.2 + 1e-9
        assert all(kitchen.robot.within_limits(q) for q in segment.configurations)


def run(kitchen: KitchenScene, name: str, args: tuple[str, ...], seed: int = 0) -> SkillTargets:
    targets = sample_targets(kitchen, name, args, np.random.default_rng(seed))
    check_targets(kitchen, targets)
    before = abstract_state(kitchen)
    targets.apply(kitchen)
    after = abstract_state(kitchen)
    assert after != before
    return targets


def test_open_drawer_pulls_it_open(build: Callable[[Path], KitchenScene]) -> None:
    kitchen = build(REPO / "pddl" / "problem.pddl")
    targets = run(kitchen, "open", ("drawer",))
    pull = next(s for s in targets.segments if s.name == "pull")
    lower, upper = kitchen.opening_limits("drawer")
    # The drawer followed the hand (as the judge derives it): open as far as the hand pulled.
    assert np.isclose(kitchen.opening("drawer"), upper, atol=2e-3)
    assert ("opened", "drawer") in abstract_state(kitchen)
    start = kitchen.robot.forward_kinematics(pull.configurations[0])
    end = kitchen.robot.forward_kinematics(pull.configurations[-1])
    assert np.isclose(np.linalg.norm(end.translation - start.translation), upper - lower, atol=2e-3)


@pytest.mark.parametrize(
    ("box", "support", "target"), [("sugar", "stove", "countertop"), ("spam", "countertop", "stove")]
)
def test_pick_and_place_on_each_surface(box: str, support: str, target: str) -> None:
    init = {("boxOn", box, support), ("surfClear", target), ("armClear",)}
    objects = {"stove": "surface", "countertop": "surface", box: "box"}
    with build_kitchen(objects, init) as kitchen:
        picked = run(kitchen, "pickUp", (box, support))
        state = abstract_state(kitchen)
        assert ("holding", box) in state and ("surfClear", support) in state
        assert ("armClear",) not in state
        # the box keeps its grasp: it moves with the arm
        hand = kitchen.robot.description.hand_link
        hand_from_box = kitchen.robot.body.link_pose(hand).inverse() @ kitchen.box(box).base_pose()
        kitchen.robot.set_configuration(picked.goal_configuration)
        moved = kitchen.robot.body.link_pose(hand).inverse() @ kitchen.box(box).base_pose()
        assert moved.distance_to(hand_from_box)[0] < 1e-6
        kitchen.robot.set_configuration(picked.final_configuration)
        run(kitchen, "placeOn", (box, target))
        state = abstract_state(kitchen)
        assert ("boxOn", box, target) in state and ("armClear",) in state
        assert ("surfClear", target) not in state


@pytest.mark.parametrize("box", ["sugar", "spam"])
def test_place_in_and_pick_from_the_drawer(box: str) -> None:
    with build_kitchen(OBJECTS, OPEN_DRAWER_INIT) as kitchen:
        support = "stove" if box == "sugar" else "countertop"
        run(kitchen, "pickUp", (box, support))
        run(kitchen, "placeIn", (box, "drawer"))
        state = abstract_state(kitchen)
        assert ("boxIn", box, "drawer") in state and ("cabClear", "drawer") not in state
        run(kitchen, "cabPickUp", (box, "drawer"))
        state = abstract_state(kitchen)
        assert ("holding", box) in state and ("cabClear", "drawer") in state


def test_same_seed_same_targets() -> None:
    with (
        build_kitchen(OBJECTS, OPEN_DRAWER_INIT) as first,
        build_kitchen(OBJECTS, OPEN_DRAWER_INIT) as second,
    ):
        a = sample_targets(first, "pickUp", ("spam", "countertop"), np.random.default_rng(7))
        b = sample_targets(second, "pickUp", ("spam", "countertop"), np.random.default_rng(7))
        assert np.array_equal(a.goal_configuration, b.goal_configuration)
        for sa, sb in zip(a.segments, b.segments, strict=True):
            assert np.array_equal(sa.configurations, sb.configurations)


def test_sampling_leaves_the_scene_unchanged(build: Callable[[Path], KitchenScene]) -> None:
    kitchen = build(REPO / "pddl" / "problem.pddl")
    before_q, before_state = kitchen.arm_configuration(), abstract_state(kitchen)
    sample_targets(kitchen, "open", ("drawer",), np.random.default_rng(0))
    sample_targets(kitchen, "pickUp", ("sugar", "stove"), np.random.default_rng(0))
    assert np.array_equal(kitchen.arm_configuration(), before_q)
    assert abstract_state(kitchen) == before_state


def test_errors_name_the_problem(build: Callable[[Path], KitchenScene]) -> None:
    kitchen = build(REPO / "pddl" / "problem.pddl")
    rng = np.random.default_rng(0)
    with pytest.raises(UnknownObjectError, match="soup"):
        sample_targets(kitchen, "pickUp", ("soup", "stove"), rng)
    with pytest.raises(UnknownActionError, match="juggle"):
        sample_targets(kitchen, "juggle", ("sugar",), rng)
    with pytest.raises(SkillFailure, match=r"\(placeOn sugar countertop\)"):
        sample_targets(kitchen, "placeOn", ("sugar", "countertop"), rng)
    with pytest.raises(SkillFailure, match="closed"):
        run(kitchen, "pickUp", ("spam", "countertop"))
        sample_targets(kitchen, "placeIn", ("spam", "drawer"), rng)
