"""Pictures of the kitchen: the scene for a problem, and the arm at each skill's targets."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.skills.registry import GroundedAction, sample_action_targets
from kitchen_tamp.kitchen.skills.targets import SkillTargets
from kitchen_tamp.world import CameraView, Image, render


def overview_camera(kitchen: KitchenScene, width: int = 640, height: int = 480) -> CameraView:
    """A view from the robot's right, towards the counter: stove, countertop, drawer front, arm."""
    low, high = kitchen.kitchen.aabb(kitchen.kitchen.base_link_name)
    base = kitchen.robot.body.base_pose().translation
    target = (
        float((base[0] + high[0]) / 2.0),
        float((low[1] + high[1]) / 2.0),
        float(0.8 * high[2]),
    )
    size = float(np.linalg.norm(high - low))
    return CameraView(target, 1.4 * size, yaw=-60.0, pitch=-28.0, width=width, height=height)


def render_scene(kitchen: KitchenScene, view: CameraView | None = None) -> Image:
    """The kitchen as it is now."""
    return render(kitchen.scene, view or overview_camera(kitchen))


@dataclass(frozen=True, eq=False)
class SkillFrame:
    """A picture of the arm at one action's key target."""

    action: str
    image: Image


def render_skill_frames(
    kitchen: KitchenScene,
    actions: list[GroundedAction],
    seed: int,
    view: CameraView | None = None,
) -> list[SkillFrame]:
    """For each action in order: sample its targets, picture the arm where its first
    scripted segment ends (grasp, handle grip or placement), then apply the action."""
    rng = np.random.default_rng(seed)
    camera = view or overview_camera(kitchen, 480, 360)
    frames = []
    for action in actions:
        targets: SkillTargets = sample_action_targets(kitchen, action, rng)
        with kitchen.scene.preserved():
            kitchen.robot.set_configuration(targets.goal_configuration)
            first = targets.segments[0]
            kitchen.robot.set_gripper_width(float(first.gripper_widths[-1]))
            kitchen.robot.set_configuration(first.configurations[-1])
            frames.append(SkillFrame(targets.action_text, render(kitchen.scene, camera)))
        targets.apply(kitchen)
    return frames
