"""pick: grasp a box where it rests, close the fingers, lift it straight up."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.abstraction import supports_of
from kitchen_tamp.kitchen.action_replay import first_problem
from kitchen_tamp.kitchen.binding import ActionBinding
from kitchen_tamp.kitchen.errors import FailureKind, SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.regions import box_corners
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.grasps import Grasp, sample_box_grasp
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.sampling_loop import Rejections, sample_skill
from kitchen_tamp.kitchen.skills.straight_moves import (
    all_valid,
    hold_still,
    reach_along_tool_axis,
    straight_move,
)
from kitchen_tamp.kitchen.skills.targets import SkillTargets, action_text
from kitchen_tamp.world import AllowedContact, FloatArray, KeptClearance, Pose, PyBulletCollisionChecker

UP = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class PickProblem:
    """What every grasp sample of one pick shares; a ``SkillProblem`` of grasps."""

    kitchen: KitchenScene
    action: tuple[str, tuple[str, ...]]
    parameters: SkillParameters
    box: str
    size: tuple[float, float, float]
    world_from_box: Pose
    lift: float
    q_now: FloatArray
    open_width: float
    max_width: float
    free_checker: PyBulletCollisionChecker
    clear_checker: PyBulletCollisionChecker
    approach_checker: PyBulletCollisionChecker
    """The grasp and the approach into it: the fingers may touch the box, the neighbour
    clearance is kept from the boxes beside it."""
    finger_contact: AllowedContact

    @property
    def action_text(self) -> str:
        return action_text(self.action)

    def draw(self, rng: np.random.Generator, rejections: Rejections) -> Grasp:
        grasp = sample_box_grasp(self.size, self.world_from_box, rng, self.max_width, self.parameters)
        if grasp is None:
            raise SkillFailure(
                self.action_text, f"{self.box} is wider than the gripper on every side", FailureKind.NO_GRASP
            )
        return grasp

    def segments(
        self, grasp: Grasp, rng: np.random.Generator, rejections: Rejections
    ) -> tuple[Segment, ...] | None:
        """Approach, close and lift for one grasp, or None if any of them is infeasible or the
        judge would find a problem replaying them."""
        kitchen, parameters = self.kitchen, self.parameters
        world_from_tool = self.world_from_box @ grasp.object_from_tool
        reached = reach_along_tool_axis(
            kitchen, world_from_tool, self.approach_checker, self.clear_checker, rng, parameters, rejections
        )
        if reached is None:
            return None
        q_grasp, approach_path = reached
        lift_path = straight_move(kitchen, q_grasp, world_from_tool, self.lift * UP, parameters)
        if lift_path is None:
            return None
        holding = _holding_checker(kitchen, self.box, q_grasp, grasp.width, self.approach_checker.kept)
        if not all_valid(holding, lift_path, rejections):
            return None
        close_qs, close_widths = hold_still(q_grasp, (self.open_width, grasp.width))
        segments = (
            Segment("approach", approach_path, np.full(len(approach_path), self.open_width)),
            Segment("close", close_qs, close_widths),
            Segment("lift", lift_path, np.full(len(lift_path), grasp.width)),
        )
        return None if first_problem(kitchen, self.action_text, self.action[1], segments) else segments

    def targets(self, segments: tuple[Segment, ...], samples_tried: int) -> SkillTargets:
        return SkillTargets(
            action=self.action,
            goal_configuration=segments[0].configurations[0],
            held_box=None,
            gripper_width=self.open_width,
            segments=segments,
            free_space_checker=self.free_checker,
            samples_tried=samples_tried,
        )

    def exhausted(self, attempts: int) -> str:
        return f"no reachable collision-free grasp in {attempts} samples"


def _holding_checker(
    kitchen: KitchenScene, box: str, q_grasp: FloatArray, width: float, kept: tuple[KeptClearance, ...]
) -> PyBulletCollisionChecker:
    """A checker of the scene with ``box`` held as it would be when grasped at ``q_grasp``,
    keeping the ``kept`` clearances."""
    with kitchen.scene.preserved():
        kitchen.robot.set_configuration(q_grasp)
        kitchen.robot.set_gripper_width(width)
        kitchen.scene.detach(kitchen.box(box))
        kitchen.grasp(box)
        return kitchen.collision_checker(kept=kept)


def sample_pick(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    binding: ActionBinding,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> SkillTargets:
    """Targets for picking the ``object`` from where it rests (the ``support`` if the action names
    one: a surface, a region, an open drawer or a box).

    Grasps are sampled on the box's faces; each is kept only if the grasp, a
    straight approach from ``pregrasp_distance`` back and a straight lift that
    clears the support (and a drawer's walls) are reachable and collision-free.
    """
    text = action_text(action)
    box = binding.argument("object", action[1])
    assert box is not None  # a required role
    held = kitchen.held_box()
    if held is not None:
        raise SkillFailure(text, f"the hand already holds {held}", FailureKind.PRECONDITION)
    support = binding.argument("support", action[1])
    if support is None:
        resting = supports_of(kitchen, box)
        if not resting:
            raise SkillFailure(text, f"{box} rests on nothing", FailureKind.PRECONDITION)
        support = resting[0][1]
    robot = kitchen.robot
    world_from_box = kitchen.box(box).base_pose()
    size = kitchen.box_size(box)
    region = kitchen.region(support)
    bottom = float(np.min(box_corners(world_from_box, size)[:, 2]))
    finger_contact = kitchen.finger_contact(box)
    with kitchen.scene.preserved():
        kitchen.set_gripper_open()
        problem = PickProblem(
            kitchen=kitchen,
            action=action,
            parameters=parameters,
            box=box,
            size=size,
            world_from_box=world_from_box,
            lift=max(parameters.lift_height, region.ceiling_z + parameters.wall_clearance - bottom),
            q_now=kitchen.arm_configuration(),
            open_width=robot.max_gripper_width,
            max_width=robot.max_gripper_width - parameters.finger_clearance,
            free_checker=kitchen.collision_checker(),
            clear_checker=kitchen.collision_checker(margin=parameters.free_space_clearance),
            approach_checker=kitchen.collision_checker(
                [finger_contact], kept=kitchen.clear_of_boxes((box, support), parameters.neighbour_clearance)
            ),
            finger_contact=finger_contact,
        )
    return sample_skill(problem, rng, parameters, Rejections(kitchen, (box,), support))
