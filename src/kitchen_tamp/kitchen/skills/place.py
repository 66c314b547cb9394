"""placeOn / placeIn: lower the held box straight onto a sampled stable pose, open the
fingers, back the hand away along the grasp's approach."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.action_replay import first_problem
from kitchen_tamp.kitchen.errors import SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.regions import SupportRegion
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.placements import Placement, down_face, face_along, sample_placement
from kitchen_tamp.kitchen.skills.straight_moves import hold_still, straight_approach, straight_move
from kitchen_tamp.kitchen.skills.targets import SkillTargets, action_text
from kitchen_tamp.world import FloatArray, Pose, PyBulletCollisionChecker

UP = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class PlaceProblem:
    """What every placement sample of one place shares."""

    box: str
    region: SupportRegion
    box_from_tool: Pose
    width: float
    q_now: FloatArray
    open_width: float
    carrying_checker: PyBulletCollisionChecker
    clear_checker: PyBulletCollisionChecker


def _released_checkers(
    kitchen: KitchenScene, box: str, q_place: FloatArray, clearance: float
) -> tuple[PyBulletCollisionChecker, PyBulletCollisionChecker]:
    """(fingers may touch the box, ``clearance`` kept from everything) checkers of the scene
    after letting go at ``q_place``."""
    robot = kitchen.robot
    with kitchen.scene.preserved():
        robot.set_configuration(q_place)
        kitchen.release(box)
        kitchen.set_gripper_open()
        touching = kitchen.collision_checker([kitchen.finger_contact(box)])
        return touching, kitchen.collision_checker(margin=clearance)


def _segments_for_placement(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    problem: PlaceProblem,
    placement: Placement,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> tuple[Segment, ...] | None:
    """Descend, release and retreat for one placement, or None if infeasible."""
    world_from_tool = placement.world_from_box @ problem.box_from_tool
    approach = world_from_tool.rotation[:, 2]
    if approach[2] > 0.1:
        return None
    q_place = kitchen.collision_free_ik(
        world_from_tool, problem.carrying_checker, rng, parameters.ik_solutions
    )
    if q_place is None:
        return None
    bottom = problem.region.top_z
    height = max(parameters.lift_height, problem.region.ceiling_z + parameters.wall_clearance - bottom)
    descent = straight_approach(kitchen, q_place, world_from_tool, -UP, height, parameters)
    if descent is None or not problem.carrying_checker.is_valid(descent).all():
        return None
    if not problem.clear_checker.is_valid(descent[0])[0]:
        return None
    retreat = straight_move(
        kitchen, q_place, world_from_tool, -parameters.pregrasp_distance * approach, parameters
    )
    if retreat is None:
        return None
    touching, clear = _released_checkers(kitchen, problem.box, q_place, parameters.free_space_clearance)
    if not touching.is_valid(retreat).all() or not clear.is_valid(retreat[-1])[0]:
        return None
    release_qs, release_widths = hold_still(q_place, (problem.width, problem.open_width))
    segments = (
        Segment("descend", descent, np.full(len(descent), problem.width)),
        Segment("release", release_qs, release_widths),
        Segment("retreat", retreat, np.full(len(retreat), problem.open_width)),
    )
    return None if first_problem(kitchen, action_text(action), action[1], segments) else segments


def sample_place(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    box: str,
    target: str,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> SkillTargets:
    """Targets for putting the held ``box`` on a surface or into an open drawer.

    Stable poses are sampled in the target region (preferring the face that was
    down when picked, then the face that puts the hand above the box); each is kept only if the hand can
    hold the box there with the grasp it has, lower it straight from above the
    region (and a drawer's walls), open the fingers and back away, all without
    collision.
    """
    text = action_text(action)
    if kitchen.held_box() != box:
        raise SkillFailure(text, f"the hand does not hold {box}")
    if target in kitchen.map.openables and not kitchen.is_opened(target):
        raise SkillFailure(text, f"{target} is closed")
    robot = kitchen.robot
    body = kitchen.box(box)
    attachment = kitchen.scene.attachment_of(body)
    assert attachment is not None
    hand_from_box = attachment.parent_link_from_child
    box_from_tool = (robot.hand_from_tool().inverse() @ hand_from_box).inverse()
    problem = PlaceProblem(
        box=box,
        region=kitchen.region(target),
        box_from_tool=box_from_tool,
        width=robot.gripper_width(),
        q_now=kitchen.arm_configuration(),
        open_width=robot.max_gripper_width,
        carrying_checker=kitchen.collision_checker(),
        clear_checker=kitchen.collision_checker(margin=parameters.free_space_clearance),
    )
    hand_above = face_along(box_from_tool.rotation[:, 2])
    preferred = (
        (down_face(body.base_pose()), parameters.keep_down_probability),
        (hand_above, parameters.hand_above_probability),
    )
    size = kitchen.box_size(box)
    for attempt in range(1, parameters.attempts + 1):
        placement = sample_placement(problem.region, size, rng, preferred)
        if placement is None:
            continue
        segments = _segments_for_placement(kitchen, action, problem, placement, rng, parameters)
        if segments is not None:
            return SkillTargets(
                action=action,
                goal_configuration=segments[0].configurations[0],
                held_box=box,
                gripper_width=problem.width,
                segments=segments,
                free_space_checker=problem.carrying_checker,
                samples_tried=attempt,
            )
    raise SkillFailure(text, f"no reachable collision-free placement in {parameters.attempts} samples")
