"""Straight Cartesian moves of the tool, solved by IK waypoint by waypoint."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.kitchen.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.parameters import SkillParameters
from kitchen_tamp.world import FloatArray, Pose, VectorLike, straight_line


def straight_move(
    kitchen: KitchenScene,
    q_start: FloatArray,
    world_from_tool_start: Pose,
    displacement: VectorLike,
    parameters: SkillParameters,
) -> FloatArray | None:
    """Joint waypoints (n, dof) moving the tool from its pose at ``q_start`` by
    ``displacement`` (world frame) in a straight line, or None if IK loses the line
    or jumps between branches."""
    waypoints = straight_line(world_from_tool_start, displacement, parameters.waypoint_step)
    return kitchen.ik.follow(q_start, waypoints, parameters.max_joint_step)


def straight_approach(
    kitchen: KitchenScene,
    q_target: FloatArray,
    world_from_tool_target: Pose,
    approach: FloatArray,
    distance: float,
    parameters: SkillParameters,
) -> FloatArray | None:
    """Waypoints that end at ``q_target`` after moving ``distance`` along ``approach``
    (solved backwards from the target, then reversed)."""
    back = straight_move(
        kitchen, q_target, world_from_tool_target, -distance * np.asarray(approach), parameters
    )
    return None if back is None else np.asarray(back[::-1])


def hold_still(q: FloatArray, widths: tuple[float, float]) -> tuple[FloatArray, FloatArray]:
    """Two identical waypoints at ``q`` with the gripper going from one width to another."""
    return np.array([q, q]), np.array(widths, dtype=float)
