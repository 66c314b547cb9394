"""The physics world leaves out only the contacts that can push nothing: between links of two
bodies that are both welded to the world (the Panda's base on its mount)."""

from __future__ import annotations

import pybullet as p

from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.planning import load_task
from kitchen_tamp.shipped_kitchens import kitchen_folder
from kitchen_tamp.world.bodies import BASE_LINK
from kitchen_tamp.world.physics import DEFAULT_PHYSICS, PhysicsWorld


def test_links_welded_to_the_world_touch_without_contacts_and_the_rest_keep_theirs() -> None:
    task = load_task(kitchen_folder("default") / "problem.pddl")
    with build_kitchen_for_task(task, polyhedral_contacts=True) as kitchen:
        robot, fixture = kitchen.robot.body, kitchen.kitchen
        world = PhysicsWorld(kitchen.scene, kitchen.robot, [fixture], list(kitchen.boxes.values()),
                             DEFAULT_PHYSICS)
        world.step(5)
        client = kitchen.scene.client

        welded = fixture.welded_links()
        assert BASE_LINK in welded and fixture.link_index("robot_mount") in welded
        assert fixture.link_index("drawer") not in welded  # on a slide
        assert fixture.link_index("drawer_handle") not in welded  # rides on the drawer
        assert robot.welded_links() == {BASE_LINK}  # the arm's first joint turns

        mount = fixture.link_index("robot_mount")
        touching = p.getClosestPoints(robot.uid, fixture.uid, 0.001, BASE_LINK, mount, physicsClientId=client)
        assert touching, "the Panda's base stands on its mount"
        contacts = p.getContactPoints(robot.uid, fixture.uid, physicsClientId=client)
        assert not [c for c in contacts if c[3] == BASE_LINK and c[4] in welded]

        sugar = kitchen.boxes["sugar"]
        resting = p.getContactPoints(sugar.uid, fixture.uid, physicsClientId=client)
        assert resting, "a box still rests on the stove"
