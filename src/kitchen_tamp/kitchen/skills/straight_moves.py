"""Straight Cartesian moves of the tool, solved by IK waypoint by waypoint."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.sampling_loop import Rejections
from kitchen_tamp.world import FloatArray, Pose, PyBulletCollisionChecker, VectorLike, straight_line


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


def reach_along_tool_axis(
    kitchen: KitchenScene,
    world_from_tool: Pose,
    contact_checker: PyBulletCollisionChecker,
    free_checker: PyBulletCollisionChecker,
    rng: np.random.Generator,
    parameters: SkillParameters,
    rejections: Rejections,
) -> tuple[FloatArray, FloatArray] | None:
    """IK for a grasp pose and the straight approach into it along the tool's z axis.

    The approach starts ``pregrasp_distance`` back, at a configuration free under
    ``free_checker`` (no contact allowed); every waypoint must pass
    ``contact_checker``, which allows the fingers to touch what they grasp.
    Returns (grasp configuration, approach waypoints) or None, noting in ``rejections`` what a
    refused configuration collided with.
    """
    q_grasp = kitchen.collision_free_ik(
        world_from_tool, contact_checker, rng, parameters.ik_solutions,
        rejected=lambda q: rejections.collided(contact_checker, q),
    )
    if q_grasp is None:
        return None
    approach_path = straight_approach(
        kitchen, q_grasp, world_from_tool, world_from_tool.rotation[:, 2], parameters.pregrasp_distance,
        parameters,
    )
    if approach_path is None:
        return None
    if not free_checker.is_valid(approach_path[0])[0]:
        rejections.collided(free_checker, approach_path[0])
        return None
    if not all_valid(contact_checker, approach_path, rejections):
        return None
    return q_grasp, approach_path


def all_valid(checker: PyBulletCollisionChecker, path: FloatArray, rejections: Rejections) -> bool:
    """Whether ``checker`` finds every waypoint of ``path`` valid (else the first refused one is
    noted in ``rejections``)."""
    valid = checker.is_valid(path)
    if valid.all():
        return True
    rejections.collided(checker, path[int(np.argmin(valid))])
    return False


def hold_still(q: FloatArray, widths: tuple[float, float]) -> tuple[FloatArray, FloatArray]:
    """Two identical waypoints at ``q`` with the gripper going from one width to another."""
    return np.array([q, q]), np.array(widths, dtype=float)
