"""open: grasp the drawer's handle bar, pull it straight along the drawer's axis with the
drawer following the hand, let go and back away."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.action_replay import first_problem, pull_direction
from kitchen_tamp.kitchen.binding import ActionBinding
from kitchen_tamp.kitchen.errors import FailureKind, SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.grasps import sample_handle_grasp
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.sampling_loop import Rejections, sample_skill
from kitchen_tamp.kitchen.skills.straight_moves import (
    all_valid,
    hold_still,
    reach_along_tool_axis,
    straight_move,
)
from kitchen_tamp.kitchen.skills.targets import SkillTargets, action_text
from kitchen_tamp.world import AllowedContact, FloatArray, Pose, PyBulletCollisionChecker


@dataclass(frozen=True)
class HandleGeometry:
    """The bar the fingers close on, and how far along it they may slide."""

    world_from_bar: Pose
    bar_size: tuple[float, float, float]
    free_half_length: float


def handle_geometry(
    kitchen: KitchenScene, openable: str, direction: FloatArray, parameters: SkillParameters
) -> HandleGeometry:
    """The handle's bar (its box shape furthest along the pull) and the free span between posts."""
    link = kitchen.map.openables[openable].handle_link
    world_from_com = kitchen.kitchen.link_com_pose(link)
    shapes = [(world_from_com @ s.com_from_box, s.size) for s in kitchen.kitchen.box_shapes(link)]
    if not shapes:
        raise SkillFailure(
            f"(open {openable})", f"handle link {link!r} has no box shapes", FailureKind.PRECONDITION
        )
    world_from_bar, bar_size = max(shapes, key=lambda s: float(np.dot(s[0].translation, direction)))
    long_axis = world_from_bar.rotation[:, int(np.argmax(bar_size))]
    free = max(bar_size) / 2.0
    for world_from_post, post_size in shapes:
        if world_from_post is world_from_bar:
            continue
        along = abs(float(np.dot(world_from_post.translation - world_from_bar.translation, long_axis)))
        post_half = float(np.abs(world_from_post.rotation.T @ long_axis) @ np.array(post_size)) / 2.0
        free = min(free, along - post_half)
    return HandleGeometry(world_from_bar, bar_size, max(0.0, free - parameters.finger_pad_half_width))


def _checkers(
    kitchen: KitchenScene, openable: str, goal: float, clearance: float
) -> tuple[
    PyBulletCollisionChecker,
    PyBulletCollisionChecker,
    PyBulletCollisionChecker,
    PyBulletCollisionChecker,
    PyBulletCollisionChecker,
]:
    """(free, free with ``clearance``, gripper-on-handle, released-after-pull, clear-after-pull) checkers."""
    handle = kitchen.handle_contact(openable)
    with kitchen.scene.preserved():
        kitchen.set_gripper_open()
        free = kitchen.collision_checker()
        clear = kitchen.collision_checker(margin=clearance)
        on_handle = kitchen.collision_checker([handle])
        kitchen.set_opening(openable, goal)
        released = kitchen.collision_checker([handle])
        return free, clear, on_handle, released, kitchen.collision_checker(margin=clearance)


HandleGrasp = tuple[Pose, float]
"""A grasp of the handle bar: the tool's pose and the finger width."""


@dataclass(frozen=True, eq=False)
class OpenProblem:
    """What every handle grasp sample of one opening shares; a ``SkillProblem`` of handle grasps."""

    kitchen: KitchenScene
    action: tuple[str, tuple[str, ...]]
    parameters: SkillParameters
    handle: HandleGeometry
    openable: str
    joint: str
    start: float
    goal: float
    pull_direction: FloatArray
    q_now: FloatArray
    open_width: float
    free_checker: PyBulletCollisionChecker
    clear_checker: PyBulletCollisionChecker
    handle_checker: PyBulletCollisionChecker
    released_checker: PyBulletCollisionChecker
    strict_released_checker: PyBulletCollisionChecker
    handle_contact: AllowedContact

    @property
    def action_text(self) -> str:
        return action_text(self.action)

    def draw(self, rng: np.random.Generator, rejections: Rejections) -> HandleGrasp:
        handle = self.handle
        return sample_handle_grasp(
            handle.world_from_bar, handle.bar_size, self.pull_direction, handle.free_half_length, rng
        )

    def segments(
        self, grasp: HandleGrasp, rng: np.random.Generator, rejections: Rejections
    ) -> tuple[Segment, ...] | None:
        """Approach, grip, pull, release and retreat for one handle grasp, or None (also when the
        judge would find a problem replaying them)."""
        kitchen, parameters = self.kitchen, self.parameters
        world_from_tool, width = grasp
        reached = reach_along_tool_axis(
            kitchen, world_from_tool, self.handle_checker, self.clear_checker, rng, parameters, rejections
        )
        if reached is None:
            return None
        q_grasp, approach_path = reached
        distance = self.goal - self.start
        pull = straight_move(kitchen, q_grasp, world_from_tool, distance * self.pull_direction, parameters)
        if pull is None:
            return None
        drawer_values = self.start + np.linspace(0.0, distance, len(pull))
        if not self.handle_checker.is_valid_along(pull, kitchen.kitchen, [self.joint], drawer_values).all():
            return None
        world_from_pulled = world_from_tool.translated(distance * self.pull_direction)
        retreat = straight_move(
            kitchen, pull[-1], world_from_pulled,
            -parameters.pregrasp_distance * world_from_tool.rotation[:, 2], parameters,
        )
        if retreat is None or not all_valid(self.released_checker, retreat, rejections):
            return None
        if not all_valid(self.strict_released_checker, retreat[-1:], rejections):
            return None
        grip_qs, grip_widths = hold_still(q_grasp, (self.open_width, width))
        release_qs, release_widths = hold_still(pull[-1], (width, self.open_width))
        open_width = self.open_width
        segments = (
            Segment("approach", approach_path, np.full(len(approach_path), open_width)),
            Segment("grip", grip_qs, grip_widths),
            Segment("pull", pull, np.full(len(pull), width)),
            Segment("release", release_qs, release_widths),
            Segment("retreat", retreat, np.full(len(retreat), open_width)),
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
        return f"no reachable collision-free handle grasp in {attempts} samples"


def sample_open(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    binding: ActionBinding,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> SkillTargets:
    """Targets for pulling the ``drawer`` fully open by its handle."""
    text = action_text(action)
    openable = binding.argument("drawer", action[1])
    assert openable is not None  # a required role
    held = kitchen.held_box()
    if held is not None:
        raise SkillFailure(text, f"the hand holds {held}", FailureKind.PRECONDITION)
    if kitchen.is_opened(openable):
        raise SkillFailure(text, f"{openable} is already open", FailureKind.PRECONDITION, region=openable)
    direction = pull_direction(kitchen, openable)
    goal = kitchen.opening_limits(openable)[1]
    free, clear, on_handle, released, strict_released = _checkers(
        kitchen, openable, goal, parameters.free_space_clearance
    )
    problem = OpenProblem(
        kitchen=kitchen,
        action=action,
        parameters=parameters,
        handle=handle_geometry(kitchen, openable, direction, parameters),
        openable=openable,
        joint=kitchen.map.openables[openable].joint,
        start=kitchen.opening(openable),
        goal=goal,
        pull_direction=direction,
        q_now=kitchen.arm_configuration(),
        open_width=kitchen.robot.max_gripper_width,
        free_checker=free,
        clear_checker=clear,
        handle_checker=on_handle,
        released_checker=released,
        strict_released_checker=strict_released,
        handle_contact=kitchen.handle_contact(openable),
    )
    return sample_skill(problem, rng, parameters, Rejections(kitchen, (), openable))
