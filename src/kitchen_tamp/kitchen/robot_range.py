"""What the robot can do at a waypoint: each arm joint within its range (the stricter of the
URDF's ``<limit>`` and ``<safety_controller>``, ``kitchen_tamp.world.Robot``) and the fingers
no wider than the hand opens and no narrower than closed.

The judge checks every waypoint of a segment before it interpolates any state
between them (a state between two waypoints in range is in range: the ranges
are boxes), and replays a segment with a waypoint out of range clipped into it,
so that the rest of the run can still be judged and pictured.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.world import Robot

RANGE_TOLERANCE: Final = 1e-9
"""Slack (rad or m) for values written at a limit (as ``Robot.within_limits``)."""


def range_problem(robot: Robot, segment: Segment) -> str | None:
    """The first waypoint of ``segment`` the robot cannot take, in words, or None."""
    qs, widths = segment.configurations, segment.gripper_widths
    below = qs < robot.lower - RANGE_TOLERANCE
    above = qs > robot.upper + RANGE_TOLERANCE
    outside = below | above
    wide = (widths < -RANGE_TOLERANCE) | (widths > robot.max_gripper_width + RANGE_TOLERANCE)
    joint_at = int(np.argmax(outside.any(axis=1))) if outside.any() else len(qs)
    width_at = int(np.argmax(wide)) if wide.any() else len(qs)
    if joint_at == len(qs) and width_at == len(qs):
        return None
    if joint_at <= width_at:
        joint = int(np.argmax(outside[joint_at]))
        low = bool(below[joint_at, joint])
        side, limit = ("lower", robot.lower[joint]) if low else ("upper", robot.upper[joint])
        name = robot.description.arm_joints[joint]
        return (
            f"waypoint {joint_at}: {name} at {qs[joint_at, joint]:.4f} rad is past its {side} limit "
            f"{limit:.4f} rad (the stricter of the URDF's <limit> and <safety_controller>)"
        )
    return (
        f"waypoint {width_at}: gripper width {widths[width_at]:.4f} m is outside the hand's range "
        f"[0, {robot.max_gripper_width:.3f}] m"
    )


def clipped_to_range(robot: Robot, segment: Segment) -> Segment:
    """``segment`` with every waypoint clipped into the robot's ranges."""
    return replace(
        segment,
        configurations=np.clip(segment.configurations, robot.lower, robot.upper),
        gripper_widths=np.clip(segment.gripper_widths, 0.0, robot.max_gripper_width),
    )
