"""Colliding and free configurations are computed from geometry, never typed in."""

from __future__ import annotations

import numpy as np
import pybullet as p
import pytest

from kitchen_tamp.world import (
    AllowedContact,
    InverseKinematics,
    KeptClearance,
    Pose,
    Robot,
    Scene,
    make_collision_checker,
)
from kitchen_tamp.world.collision.checked_pairs import CONTACT_PENETRATION_BOUND
from tests.world.conftest import down_rotation


def above_and_inside_counter(scene: Scene, robot: Robot) -> tuple[np.ndarray, np.ndarray]:
    """(free, colliding) arm configurations: tool 0.3 m above the counter's slab and
    tool in the middle of the slab, both over the countertop area."""
    kitchen = scene.body("kitchen")
    low, high = kitchen.aabb("countertop")
    x, y = float((low[0] + high[0]) / 2.0), float((low[1] + high[1]) / 2.0)
    _, slab_high = kitchen.aabb("cabinet")
    ik = InverseKinematics(robot)
    rng = np.random.default_rng(0)
    free = ik.solve(Pose.from_rotation((x, y, float(high[2]) + 0.3), down_rotation()), rng)
    inside = ik.solve(Pose.from_rotation((x, y, float(slab_high[2]) - 0.02), down_rotation()), rng)
    assert free is not None and inside is not None
    return free, inside


def test_free_and_colliding_configurations(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    free, inside = above_and_inside_counter(scene, robot)
    checker = make_collision_checker(scene, robot)
    valid = checker.is_valid(np.stack([free, inside]))
    assert valid.dtype == bool and valid.shape == (2,)
    assert valid.tolist() == [True, False]
    assert any(other.startswith("kitchen/") for _, other in checker.colliding_pairs(inside))


def test_configuration_outside_limits_is_invalid(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    checker = make_collision_checker(scene, robot)
    assert not checker.is_valid(robot.upper + 0.1)[0]


def test_segment_validity_and_fail_fast(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    free, inside = above_and_inside_counter(scene, robot)
    checker = make_collision_checker(scene, robot)
    assert checker.segment_valid(free, free)
    assert not checker.segment_valid(free, inside)


def test_min_clearance_sign(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    free, inside = above_and_inside_counter(scene, robot)
    clearance = make_collision_checker(scene, robot).min_clearance(np.stack([free, inside]))
    assert clearance[0] > 0.0 > clearance[1]


def test_checks_leave_the_arm_where_it_was(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    free, inside = above_and_inside_counter(scene, robot)
    before = robot.configuration()
    checker = make_collision_checker(scene, robot)
    checker.is_valid(np.stack([free, inside]))
    checker.segment_valid(free, inside)
    checker.min_clearance(inside)
    assert np.array_equal(robot.configuration(), before)


def test_allowed_contact_ignores_only_that_link(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    _, inside = above_and_inside_counter(scene, robot)
    unbounded = AllowedContact("kitchen", max_penetration=float("inf"))
    all_kitchen = make_collision_checker(scene, robot, [unbounded])
    assert not any(other.startswith("kitchen") for _, other in all_kitchen.colliding_pairs(inside))
    only_handle = AllowedContact("kitchen", "drawer_handle", robot.gripper_links)
    assert not make_collision_checker(scene, robot, [only_handle]).is_valid(inside)[0]


def test_an_allowed_contact_is_bounded_in_depth(panda_scene: tuple[Scene, Robot]) -> None:
    """Contact with the whole kitchen allowed at the default bound: the hand deep in the
    counter is still a collision, named, and its clearance counts from the bound."""
    scene, robot = panda_scene
    _, inside = above_and_inside_counter(scene, robot)
    bounded = make_collision_checker(scene, robot, [AllowedContact("kitchen")])
    strict = make_collision_checker(scene, robot)
    assert not bounded.is_valid(inside)[0]
    assert any(other.startswith("kitchen") for _, other in bounded.colliding_pairs(inside))
    assert bounded.min_clearance(inside)[0] == pytest.approx(
        strict.min_clearance(inside)[0] + CONTACT_PENETRATION_BOUND, abs=1e-6
    )


def test_self_collision_is_detected(panda_scene: tuple[Scene, Robot]) -> None:
    """Fold the hand back onto the base: found by sampling, checked against a checker with
    every other body allowed, so only self-collision can make it invalid."""
    scene, robot = panda_scene
    unbounded = float("inf")
    others = [b for b in scene.bodies if b is not robot.body]
    allow_world = [AllowedContact(b.name, max_penetration=unbounded) for b in others]
    checker = make_collision_checker(scene, robot, allow_world)
    rng = np.random.default_rng(0)
    samples = rng.uniform(robot.lower, robot.upper, size=(400, robot.dof))
    valid = checker.is_valid(samples)
    assert valid.any() and not valid.all()
    pairs = checker.colliding_pairs(samples[np.argmin(valid)])
    assert pairs and all(a.startswith("panda") and b.startswith("panda") for a, b in pairs)


def test_carried_box_is_checked(panda_scene: tuple[Scene, Robot]) -> None:
    """A box attached to the hand collides when the hand goes down into the counter."""
    scene, robot = panda_scene
    box = scene.body("sugar")
    free, _ = above_and_inside_counter(scene, robot)
    robot.set_configuration(free)
    world_from_tool = robot.tool_pose()
    box.reset_base_pose(world_from_tool.translated((0.0, 0.0, -0.05)))
    scene.attach(box, robot.body, robot.description.hand_link)
    checker = make_collision_checker(scene, robot)
    assert checker.is_valid(free)[0]
    ik = InverseKinematics(robot)
    lowered = ik.solve(world_from_tool.translated((0.0, 0.0, -0.2)), np.random.default_rng(0), [free])
    assert lowered is not None
    assert not checker.is_valid(lowered)[0]
    assert any(a == "sugar" for a, _ in checker.colliding_pairs(lowered))


@pytest.mark.parametrize("resolution", [0.05, 0.01])
def test_segment_valid_between_free_configurations(
    panda_scene: tuple[Scene, Robot], resolution: float
) -> None:
    scene, robot = panda_scene
    free, _ = above_and_inside_counter(scene, robot)
    nearby = free.copy()
    nearby[0] += 0.2
    checker = make_collision_checker(scene, robot)
    assert checker.segment_valid(free, nearby, resolution_rad=resolution)


def test_a_kept_clearance_holds_only_for_its_body(panda_scene: tuple[Scene, Robot]) -> None:
    """A box set beside the hand a measured few millimetres away: a kept clearance larger
    than the gap makes the configuration collide (naming the box), a smaller one does not,
    one kept from another body changes nothing, and an intended contact overrides it."""
    scene, robot = panda_scene
    free, _ = above_and_inside_counter(scene, robot)
    robot.set_configuration(free)
    box = scene.body("sugar")
    height = box.box_shapes("sugar")[0].size[2]
    box.reset_base_pose(robot.tool_pose().translated((0.0, 0.0, -0.5 * height - 0.02)))
    closest = p.getClosestPoints(robot.body.uid, box.uid, 0.1, physicsClientId=box.client)
    gap = min(float(point[8]) for point in closest)
    assert 0.003 < gap < 0.05
    wider = make_collision_checker(scene, robot, kept=[KeptClearance("sugar", gap + 0.002)])
    narrower = make_collision_checker(scene, robot, kept=[KeptClearance("sugar", gap - 0.002)])
    elsewhere = make_collision_checker(
        scene, robot, kept=[KeptClearance("kitchen", 0.0), KeptClearance("none", 1.0)]
    )
    assert not wider.is_valid(free)[0]
    assert any(other.startswith("sugar/") for _, other in wider.colliding_pairs(free))
    assert narrower.is_valid(free)[0] and elsewhere.is_valid(free)[0]
    touching = make_collision_checker(
        scene, robot, [AllowedContact("sugar")], kept=[KeptClearance("sugar", 1.0)]
    )
    assert touching.is_valid(free)[0]
