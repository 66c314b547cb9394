from __future__ import annotations

import numpy as np

from kitchen_tamp.world import Robot, Scene


def test_attached_box_keeps_its_pose_relative_to_the_hand(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    box = scene.body("sugar")
    hand = robot.description.hand_link
    attachment = scene.attach(box, robot.body, hand)
    hand_from_box = robot.body.link_pose(hand).inverse() @ box.base_pose()
    rng = np.random.default_rng(0)
    for _ in range(5):
        robot.set_configuration(rng.uniform(robot.lower, robot.upper))
        now = robot.body.link_pose(hand).inverse() @ box.base_pose()
        position_error, angle_error = now.distance_to(hand_from_box)
        assert position_error < 1e-6 and angle_error < 1e-5
    assert attachment.parent_link_from_child.distance_to(hand_from_box)[0] < 1e-9


def test_detached_box_stays_put(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    box = scene.body("sugar")
    scene.attach(box, robot.body, robot.description.hand_link)
    robot.set_configuration(robot.mid_configuration() + 0.1)
    scene.detach(box)
    resting = box.base_pose()
    robot.set_configuration(robot.mid_configuration())
    assert box.base_pose().distance_to(resting)[0] < 1e-12
    assert scene.attachment_of(box) is None


def test_box_in_drawer_rides_with_the_drawer(panda_scene: tuple[Scene, Robot]) -> None:
    scene, _ = panda_scene
    kitchen, box = scene.body("kitchen"), scene.body("sugar")
    scene.attach(box, kitchen, "drawer")
    before = box.base_pose().translation
    scene.set_joint_positions(kitchen, ["drawer_joint"], [0.1])
    moved = box.base_pose().translation - before
    assert np.isclose(np.linalg.norm(moved), 0.1)
