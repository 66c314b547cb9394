"""The scene description is plain data that rebuilds the scene: bodies, poses, joints, attachments."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.world import AllowedContact, Pose, Robot, Scene, UnknownNameError, make_collision_checker
from kitchen_tamp.world.scene_description import (
    SceneDescription,
    describe_collision_checker,
    describe_scene,
)
from tests.world.conftest import MODELS


def urdf_paths(robot: Robot) -> dict[str, Path | str]:
    from kitchen_tamp.world import panda_urdf_path

    return {"kitchen": MODELS / "kitchen.urdf", "panda": panda_urdf_path(), "sugar": MODELS / "sugar.urdf"}


def hold_sugar(scene: Scene, robot: Robot) -> None:
    box = scene.body("sugar")
    box.reset_base_pose(robot.tool_pose().translated((0.0, 0.0, -0.03)))
    scene.attach(box, robot.body, robot.description.hand_link)


def plain_values(value: Any) -> list[Any]:
    """Every leaf value reachable through dataclass fields, sequences and mappings."""
    if hasattr(value, "__dataclass_fields__"):
        return [leaf for name in value.__dataclass_fields__ for leaf in plain_values(getattr(value, name))]
    if isinstance(value, Mapping):
        return [leaf for item in value.items() for leaf in plain_values(item)]
    if isinstance(value, tuple | frozenset | list):
        return [leaf for item in value for leaf in plain_values(item)]
    return [value]


def test_every_body_is_described_as_it_stands(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    kitchen = scene.body("kitchen")
    scene.set_joint_positions(kitchen, ["drawer_joint"], [0.1])
    description = describe_scene(scene, robot, urdf_paths(robot))
    assert [b.name for b in description.bodies] == [b.name for b in scene.bodies]
    for body in scene.bodies:
        described = description.body(body.name)
        assert Path(described.urdf_path).is_file()
        assert described.base_link == body.base_link_name
        assert np.allclose(described.world_from_base, body.base_pose().matrix())
        movable = [j.name for j in body.joints if j.movable]
        assert list(described.joint_positions) == movable
        if movable:
            assert np.allclose(list(described.joint_positions.values()), body.joint_positions(movable))
        assert not described.world_from_base.flags.writeable
    assert description.body("kitchen").joint_positions["drawer_joint"] == pytest.approx(0.1)
    assert description.robot == "panda" and description.arm_joints == robot.description.arm_joints
    assert np.array_equal(description.arm_configuration, robot.configuration())
    assert (
        np.array_equal(description.arm_lower, robot.lower)
        and description.gripper_links == robot.gripper_links
    )
    assert description.attachments == () and description.carried == ()


def test_description_is_plain_data(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    hold_sugar(scene, robot)
    allowed = (AllowedContact("kitchen", "drawer_handle", robot.gripper_links),)
    description = describe_scene(scene, robot, urdf_paths(robot), allowed)
    assert any(pair.allowance > 0 and pair.link_b == "drawer_handle" for pair in description.checked_pairs)
    kinds = {type(leaf) for leaf in plain_values(description)}
    assert kinds <= {str, float, np.ndarray, type(None)}, kinds


def test_attachment_keeps_the_carried_box_on_the_hand(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    hold_sugar(scene, robot)
    description = describe_scene(scene, robot, urdf_paths(robot))
    (attachment,) = description.attachments
    assert (attachment.parent, attachment.parent_link, attachment.child) == ("panda", "panda_hand", "sugar")
    assert description.carried == ("sugar",)
    world_from_hand = robot.body.link_pose("panda_hand").matrix()
    world_from_box = world_from_hand @ attachment.parent_link_from_child
    assert np.allclose(world_from_box, description.body("sugar").world_from_base, atol=1e-9)


def test_checker_description_is_the_captured_snapshot(panda_scene: tuple[Scene, Robot]) -> None:
    """Captured while holding the box with the drawer shut; described after both changed."""
    scene, robot = panda_scene
    hold_sugar(scene, robot)
    allowed = [AllowedContact("sugar", robot_links=robot.finger_links)]
    checker = make_collision_checker(scene, robot, allowed)
    captured = describe_scene(scene, robot, urdf_paths(robot), allowed)
    kitchen, box = scene.body("kitchen"), scene.body("sugar")
    scene.detach(box)
    scene.set_base_pose(box, Pose((2.0, 0.0, 1.0)))
    scene.set_joint_positions(kitchen, ["drawer_joint"], [0.2])
    robot.set_configuration(robot.lower + 0.2)
    before = scene.save_state()
    described = describe_collision_checker(checker, urdf_paths(robot))
    assert scene.attachments == before.attachments and scene.attachment_of(box) is None
    assert np.allclose(robot.configuration(), robot.lower + 0.2)
    assert described.checked_pairs == captured.checked_pairs
    assert [a.child for a in described.attachments] == ["sugar"]
    for expected, found in zip(captured.bodies, described.bodies, strict=True):
        assert np.allclose(found.world_from_base, expected.world_from_base, atol=1e-9)
        assert dict(found.joint_positions) == pytest.approx(dict(expected.joint_positions))
    assert isinstance(described, SceneDescription)


def test_missing_urdf_path_is_named(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    paths = urdf_paths(robot)
    del paths["sugar"]
    with pytest.raises(UnknownNameError, match="sugar"):
        describe_scene(scene, robot, paths)


def test_urdf_paths_default_to_the_files_the_scene_loaded(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    recorded = describe_scene(scene, robot)
    given = describe_scene(scene, robot, urdf_paths(robot))
    assert [(b.name, b.urdf_path) for b in recorded.bodies] == [(b.name, b.urdf_path) for b in given.bodies]
