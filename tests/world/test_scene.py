from __future__ import annotations

import pybullet as p
import pytest

from kitchen_tamp.world import Robot, Scene, UnknownNameError


def test_close_disconnects_and_is_idempotent() -> None:
    scene = Scene()
    client = scene.client
    scene.close()
    scene.close()
    assert not p.isConnected(physicsClientId=client)


def test_context_manager_disconnects_on_error() -> None:
    with pytest.raises(RuntimeError), Scene() as scene:
        client = scene.client
        raise RuntimeError("boom")
    assert not p.isConnected(physicsClientId=client)


def test_unknown_names_raise(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    with pytest.raises(UnknownNameError, match="toaster"):
        scene.body("toaster")
    with pytest.raises(UnknownNameError, match="panda_link99"):
        robot.body.link_index("panda_link99")
    with pytest.raises(UnknownNameError, match="elbow"):
        robot.body.joint("elbow")


def test_links_and_joints_by_name(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    kitchen = scene.body("kitchen")
    assert kitchen.joint("drawer_joint").movable
    assert kitchen.link_name(kitchen.link_index("drawer_handle")) == "drawer_handle"
    assert robot.dof == 7
    assert robot.max_gripper_width > 0.07


def test_preserved_restores_joints_and_poses(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    kitchen = scene.body("kitchen")
    before_q = robot.configuration()
    before_box = scene.body("sugar").base_pose()
    with scene.preserved():
        robot.set_configuration(robot.lower)
        scene.set_joint_positions(kitchen, ["drawer_joint"], [0.2])
        scene.body("sugar").reset_base_pose(before_box.translated((0.1, 0.0, 0.0)))
    assert (robot.configuration() == before_q).all()
    assert kitchen.joint_positions(["drawer_joint"])[0] == 0.0
    assert scene.body("sugar").base_pose().distance_to(before_box)[0] < 1e-9
