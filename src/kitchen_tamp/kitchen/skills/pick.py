"""pickUp / cabPickUp: grasp a box where it rests, close the fingers, lift it straight up."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.action_replay import first_problem
from kitchen_tamp.kitchen.errors import SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.regions import box_corners
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.grasps import Grasp, sample_box_grasp
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.straight_moves import hold_still, reach_along_tool_axis, straight_move
from kitchen_tamp.kitchen.skills.targets import SkillTargets, action_text
from kitchen_tamp.world import AllowedContact, FloatArray, Pose, PyBulletCollisionChecker

UP = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class PickProblem:
    """What every grasp sample of one pick shares."""

    box: str
    world_from_box: Pose
    lift: float
    q_now: FloatArray
    open_width: float
    free_checker: PyBulletCollisionChecker
    clear_checker: PyBulletCollisionChecker
    approach_checker: PyBulletCollisionChecker
    finger_contact: AllowedContact


def _holding_checker(
    kitchen: KitchenScene, box: str, q_grasp: FloatArray, width: float
) -> PyBulletCollisionChecker:
    """A checker of the scene with ``box`` held as it would be when grasped at ``q_grasp``."""
    with kitchen.scene.preserved():
        kitchen.robot.set_configuration(q_grasp)
        kitchen.robot.set_gripper_width(width)
        kitchen.scene.detach(kitchen.box(box))
        kitchen.grasp(box)
        return kitchen.collision_checker()


def _segments_for_grasp(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    problem: PickProblem,
    grasp: Grasp,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> tuple[Segment, ...] | None:
    """Approach, close and lift for one grasp, or None if any of them is infeasible or the
    judge would find a problem replaying them."""
    world_from_tool = problem.world_from_box @ grasp.object_from_tool
    reached = reach_along_tool_axis(
        kitchen, world_from_tool, problem.approach_checker, problem.clear_checker, rng, parameters
    )
    if reached is None:
        return None
    q_grasp, approach_path = reached
    lift_path = straight_move(kitchen, q_grasp, world_from_tool, problem.lift * UP, parameters)
    if lift_path is None:
        return None
    if not _holding_checker(kitchen, problem.box, q_grasp, grasp.width).is_valid(lift_path).all():
        return None
    close_qs, close_widths = hold_still(q_grasp, (problem.open_width, grasp.width))
    segments = (
        Segment("approach", approach_path, np.full(len(approach_path), problem.open_width)),
        Segment("close", close_qs, close_widths),
        Segment("lift", lift_path, np.full(len(lift_path), grasp.width)),
    )
    return None if first_problem(kitchen, action_text(action), action[1], segments) else segments


def sample_pick(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    box: str,
    support: str,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> SkillTargets:
    """Targets for picking ``box`` from ``support`` (a surface or an open drawer).

    Grasps are sampled on the box's faces; each is kept only if the grasp, a
    straight approach from ``pregrasp_distance`` back and a straight lift that
    clears the support (and a drawer's walls) are reachable and collision-free.
    """
    text = action_text(action)
    held = kitchen.held_box()
    if held is not None:
        raise SkillFailure(text, f"the hand already holds {held}")
    robot = kitchen.robot
    world_from_box = kitchen.box(box).base_pose()
    size = kitchen.box_size(box)
    region = kitchen.region(support)
    bottom = float(np.min(box_corners(world_from_box, size)[:, 2]))
    finger_contact = kitchen.finger_contact(box)
    with kitchen.scene.preserved():
        kitchen.set_gripper_open()
        problem = PickProblem(
            box=box,
            world_from_box=world_from_box,
            lift=max(parameters.lift_height, region.ceiling_z + parameters.wall_clearance - bottom),
            q_now=kitchen.arm_configuration(),
            open_width=robot.max_gripper_width,
            free_checker=kitchen.collision_checker(),
            clear_checker=kitchen.collision_checker(margin=parameters.free_space_clearance),
            approach_checker=kitchen.collision_checker([finger_contact]),
            finger_contact=finger_contact,
        )
    max_width = robot.max_gripper_width - parameters.finger_clearance
    for attempt in range(1, parameters.attempts + 1):
        grasp = sample_box_grasp(size, world_from_box, rng, max_width, parameters)
        if grasp is None:
            raise SkillFailure(text, f"{box} is wider than the gripper on every side")
        segments = _segments_for_grasp(kitchen, action, problem, grasp, rng, parameters)
        if segments is not None:
            return SkillTargets(
                action=action,
                goal_configuration=segments[0].configurations[0],
                held_box=None,
                gripper_width=problem.open_width,
                segments=segments,
                free_space_checker=problem.free_checker,
                samples_tried=attempt,
            )
    raise SkillFailure(text, f"no reachable collision-free grasp in {parameters.attempts} samples")
