"""Bodies riding a moving drawer are checked against the cabinet, and overlapping layouts
are found (with the bodies and links named)."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.world import Pose, Robot, Scene, make_collision_checker
from kitchen_tamp.world.contacts import overlapping_links
from tests.world.conftest import MODELS


def _baguette_standing_in_the_open_drawer(scene: Scene) -> None:
    kitchen = scene.body("kitchen")
    scene.set_joint_positions(kitchen, ["drawer_joint"], [kitchen.joint("drawer_joint").upper])
    low, high = kitchen.aabb("drawer_floor")
    baguette = scene.load_urdf("baguette", MODELS / "baguette.urdf")
    centre = (low + high) / 2.0
    baguette.reset_base_pose(Pose((float(centre[0]), float(centre[1]), float(high[2]) + 0.251)))
    scene.attach(baguette, kitchen, "drawer")


def test_a_box_riding_the_drawer_is_checked_against_the_cabinet(panda_scene: tuple[Scene, Robot]) -> None:
    """A tall box standing in the open drawer: closing the drawer drives it into the counter."""
    scene, robot = panda_scene
    _baguette_standing_in_the_open_drawer(scene)
    checker = make_collision_checker(scene, robot)
    joint = scene.body("kitchen").joint("drawer_joint")
    q = robot.configuration()
    closing = np.linspace(joint.upper, joint.lower, 8)
    pairs_open = checker.colliding_pairs(q, (scene.body("kitchen"), ["drawer_joint"], closing[:1]))
    pairs_shut = checker.colliding_pairs(q, (scene.body("kitchen"), ["drawer_joint"], closing[-1:]))
    assert not any(a == "baguette" for a, _ in pairs_open), pairs_open
    assert any(a == "baguette" and b.startswith("kitchen/") for a, b in pairs_shut), pairs_shut
    valid = checker.is_valid_along(np.tile(q, (8, 1)), scene.body("kitchen"), ["drawer_joint"], closing)
    assert valid[0] and not valid[-1]
    # with the drawer standing still, nothing moves the box: the arm alone is checked
    assert checker.is_valid(q)[0] == (not any(a.startswith("panda") for a, _ in pairs_open))


def test_overlapping_bodies_are_named(panda_scene: tuple[Scene, Robot]) -> None:
    scene, _ = panda_scene
    assert not [o for o in overlapping_links(scene, 0.002) if "sugar" in (o.first + o.second)]
    sugar = scene.body("sugar")
    pose = sugar.base_pose()
    sugar.reset_base_pose(pose.translated((0.0, 0.0, -0.05)))
    found = [o for o in overlapping_links(scene, 0.002) if "sugar" in (o.first + o.second)]
    assert ("kitchen/stove", "sugar/sugar") in [(o.first, o.second) for o in found]
    assert 0.045 < max(o.depth for o in found) < 0.055
