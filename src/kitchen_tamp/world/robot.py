"""An arm with a parallel gripper: joints, limits, gripper width and forward kinematics by name.

An arm joint's range is the stricter of its URDF ``<limit>`` and its
``<safety_controller>`` soft limits (for the Panda of ``pybullet_data``: the
datasheet's limits, 0.0698 rad -- 4 degrees -- inside its ``<limit>`` on every joint),
so planners, IK and the judge all keep to what the robot may do, not to where it stops.
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray, Pose


@dataclass(frozen=True)
class ArmDescription:
    """Names that tell an arm body's joints and links apart (no indices)."""

    arm_joints: tuple[str, ...]
    finger_joints: tuple[str, ...]
    hand_link: str
    tool_link: str
    """The frame grasps are defined in: origin between the finger pads, z along the approach."""


PANDA = ArmDescription(
    arm_joints=tuple(f"panda_joint{i}" for i in range(1, 8)),
    finger_joints=("panda_finger_joint1", "panda_finger_joint2"),
    hand_link="panda_hand",
    tool_link="panda_grasptarget",
)


def safety_limits(urdf: Path) -> dict[str, tuple[float, float]]:
    """Joint name -> (soft lower, soft upper) of every joint with a ``<safety_controller>`` that
    states both (empty when the file cannot be read: PyBullet loaded it, so that is rare)."""
    try:
        root = ElementTree.parse(urdf).getroot()
    except (OSError, ElementTree.ParseError):
        return {}
    limits = {}
    for joint in root.iter("joint"):
        safety = joint.find("safety_controller")
        if safety is None or joint.get("name") is None:
            continue
        lower, upper = safety.get("soft_lower_limit"), safety.get("soft_upper_limit")
        if lower is not None and upper is not None:
            limits[str(joint.get("name"))] = (float(lower), float(upper))
    return limits


def _stricter(
    urdf: tuple[float, float], safety: Mapping[str, tuple[float, float]], name: str
) -> tuple[float, float]:
    soft = safety.get(name, urdf)
    return max(urdf[0], soft[0]), min(urdf[1], soft[1])


class Robot:
    """An arm body in a scene; changes go through the scene so attached boxes follow.

    ``lower`` and ``upper`` are the arm joints' ranges: the stricter of the URDF's
    ``<limit>`` (``urdf_lower``, ``urdf_upper``) and its ``<safety_controller>``."""

    def __init__(self, scene: Scene, body: Body, description: ArmDescription) -> None:
        self.scene = scene
        self.body = body
        self.description = description
        joints = [body.joint(n) for n in description.arm_joints]
        self.urdf_lower: FloatArray = np.array([j.lower for j in joints])
        self.urdf_upper: FloatArray = np.array([j.upper for j in joints])
        urdf = scene.urdf_paths.get(body.name)
        safety = safety_limits(urdf) if urdf is not None else {}
        ranges = [_stricter((j.lower, j.upper), safety, j.name) for j in joints]
        self.lower: FloatArray = np.array([low for low, _ in ranges])
        self.upper: FloatArray = np.array([high for _, high in ranges])
        fingers = [body.joint(n) for n in description.finger_joints]
        self.max_gripper_width: float = float(sum(f.upper for f in fingers))
        self.gripper_links: frozenset[str] = frozenset(
            {description.hand_link, description.tool_link} | {f.child_link for f in fingers}
        )
        self.finger_links: frozenset[str] = frozenset(f.child_link for f in fingers)
        body.link_index(description.tool_link)

    @property
    def dof(self) -> int:
        """Number of arm joints."""
        return len(self.description.arm_joints)

    # -- configuration -------------------------------------------------------------------------
    def configuration(self) -> FloatArray:
        """Current arm joint positions."""
        return self.body.joint_positions(self.description.arm_joints)

    def set_configuration(self, q: Sequence[float] | FloatArray) -> None:
        """Move the arm (and whatever it carries)."""
        self.scene.set_joint_positions(self.body, self.description.arm_joints, list(q))

    def within_limits(self, q: FloatArray, tolerance: float = 1e-9) -> bool:
        """Whether ``q`` respects every joint limit."""
        return bool(np.all(q >= self.lower - tolerance) and np.all(q <= self.upper + tolerance))

    def gripper_width(self) -> float:
        """Distance between the fingers."""
        return float(np.sum(self.body.joint_positions(self.description.finger_joints)))

    def set_gripper_width(self, width: float) -> None:
        """Open or close the fingers symmetrically to ``width`` (clipped to what they can do)."""
        half = float(np.clip(width, 0.0, self.max_gripper_width)) / 2.0
        fingers = self.description.finger_joints
        self.scene.set_joint_positions(self.body, fingers, [half] * len(fingers))

    # -- forward kinematics ---------------------------------------------------------------------
    def tool_pose(self) -> Pose:
        """``world_from_tool`` at the current configuration."""
        return self.body.link_pose(self.description.tool_link)

    def forward_kinematics(self, q: Sequence[float] | FloatArray, link: str | None = None) -> Pose:
        """``world_from_link`` (tool link by default) at ``q``; the arm is left where it was."""
        saved = self.configuration()
        self.body.reset_joint_positions(self.description.arm_joints, list(q))
        pose = self.body.link_pose(link or self.description.tool_link)
        self.body.reset_joint_positions(self.description.arm_joints, list(saved))
        return pose

    def hand_from_tool(self) -> Pose:
        """The fixed transform from the hand link to the tool frame."""
        return self.body.link_pose(self.description.hand_link).inverse() @ self.tool_pose()

    def mid_configuration(self) -> FloatArray:
        """The middle of every joint range."""
        return np.asarray((self.lower + self.upper) / 2.0)
