"""Fixtures for world tests: a DIRECT scene that always disconnects, and the kitchen
counter with the Panda on its mount (loaded through the world API only)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.world import PANDA, Body, Pose, Robot, Scene, panda_urdf_path

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.fixture
def scene() -> Iterator[Scene]:
    with Scene() as created:
        yield created
    assert not created.connected


@pytest.fixture
def panda_scene(scene: Scene) -> tuple[Scene, Robot]:
    """Kitchen counter, Panda on the mount link's top face, a sugar box on the stove."""
    kitchen = scene.load_urdf("kitchen", MODELS / "kitchen.urdf", fixed_base=True)
    mount_top = float(kitchen.aabb("robot_mount")[1][2]) - 0.001
    panda = scene.load_urdf("panda", panda_urdf_path(), Pose((0.0, 0.0, mount_top)), fixed_base=True)
    robot = Robot(scene, panda, PANDA)
    robot.set_configuration(robot.mid_configuration())
    robot.set_gripper_width(robot.max_gripper_width)
    stove_low, stove_high = kitchen.aabb("stove")
    centre = (stove_low + stove_high) / 2.0
    box = scene.load_urdf("sugar", MODELS / "sugar.urdf")
    half_height = box.box_shapes("sugar")[0].size[2] / 2.0
    box.reset_base_pose(Pose((float(centre[0]), float(centre[1]), float(stove_high[2]) + half_height)))
    return scene, robot


def down_rotation() -> np.ndarray:
    """Tool z pointing down."""
    return np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])


def sugar_riding_in_drawer(scene: Scene) -> Body:
    """The kitchen, with the sugar box attached to its drawer's floor, so that it slides with it."""
    kitchen, box = scene.body("kitchen"), scene.body("sugar")
    box.reset_base_pose(kitchen.link_pose("drawer_floor").translated((0.0, 0.0, 0.1)))
    scene.attach(box, kitchen, "drawer_floor")
    return kitchen
