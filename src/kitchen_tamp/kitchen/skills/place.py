"""place / place_in / stack: lower the held box straight onto a sampled stable pose clear of
the boxes already there, open the fingers, back the hand away along the grasp's approach."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.kitchen.abstraction import RESTING_TOLERANCE
from kitchen_tamp.kitchen.action_replay import first_problem
from kitchen_tamp.kitchen.binding import ActionBinding
from kitchen_tamp.kitchen.errors import FailureKind, SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.regions import SupportRegion, box_corners
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.packing import box_footprint, packed_placements, region_footprint
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.placements import (
    Placement,
    boxes_overlap,
    down_face,
    face_along,
    fits_somewhere,
    overlaps_region,
    sample_placement,
)
from kitchen_tamp.kitchen.skills.sampling_loop import Rejections, sample_skill
from kitchen_tamp.kitchen.skills.straight_moves import all_valid, hold_still, straight_approach, straight_move
from kitchen_tamp.kitchen.skills.targets import SkillTargets, action_text
from kitchen_tamp.world import FloatArray, KeptClearance, Pose, PyBulletCollisionChecker

UP = np.array([0.0, 0.0, 1.0])


Neighbour = tuple[str, Pose, tuple[float, float, float]]
"""A box already in the scene: its name, pose and size."""


@dataclass
class PackedQueue:
    """The packed placements of one place (``kitchen.skills.packing``), computed when first
    needed and handed out in turn, round and round (each try draws its own IK)."""

    placements: list[Placement] | None = None
    handed_out: int = 0

    def next(self, compute: Callable[[], list[Placement]]) -> Placement | None:
        if self.placements is None:
            self.placements = compute()
        if not self.placements:
            return None
        placement = self.placements[self.handed_out % len(self.placements)]
        self.handed_out += 1
        return placement


@dataclass(frozen=True, eq=False)
class PlaceProblem:
    """What every placement sample of one place shares; a ``SkillProblem`` of placements."""

    kitchen: KitchenScene
    action: tuple[str, tuple[str, ...]]
    parameters: SkillParameters
    box: str
    size: tuple[float, float, float]
    region: SupportRegion
    preferred: tuple[tuple[tuple[int, int], float], ...]
    centre_inset: float | None
    """Stacking: how far inside the top face the box's centre stays (None: its footprint does)."""
    neighbours: tuple[Neighbour, ...]
    excluded: tuple[SupportRegion, ...]
    """Regions on the target surface: a box put on the surface stays off them."""
    box_from_tool: Pose
    width: float
    q_now: FloatArray
    open_width: float
    carrying_checker: PyBulletCollisionChecker
    """The scene with the box held, for the free-space motion to the place."""
    descent_checker: PyBulletCollisionChecker
    """The place and the descent onto it: the neighbour clearance kept from the boxes there."""
    clear_checker: PyBulletCollisionChecker
    packed: PackedQueue = field(default_factory=PackedQueue)

    @property
    def action_text(self) -> str:
        return action_text(self.action)

    def draw(self, rng: np.random.Generator, rejections: Rejections) -> Placement | None:
        """A stable pose in the region clear of the boxes there, or None: on a region that holds
        boxes, with ``packed_probability`` the next packed pose (flush against the region's edges
        and the boxes there); else up to ``placement_draws`` uniform draws (which cost no
        motion), and the next packed pose when none of them was clear."""
        packing = self.centre_inset is None
        if packing and self.occupied() and rng.random() < self.parameters.packed_probability:
            return self.next_packed(rng, rejections)
        for _ in range(self.parameters.placement_draws):
            placement = sample_placement(self.region, self.size, rng, self.preferred, self.centre_inset)
            if placement is None:
                return None
            crowded = self.crowding(placement.world_from_box)
            if crowded is not None and rejections.placement(crowded):
                return placement
        return self.next_packed(rng, rejections) if packing else None

    def next_packed(self, rng: np.random.Generator, rejections: Rejections) -> Placement | None:
        placement = self.packed.next(lambda: self.packed_placements(rng))
        if placement is not None:
            rejections.placement([])
        return placement

    def occupied(self) -> bool:
        """Whether some box stands on the region (its centre over it, its bottom near it)."""
        top = self.region.top_z
        return any(
            self.region.contains_xy(at.translation)
            and abs(box_corners(at, size)[:, 2].min() - top) <= RESTING_TOLERANCE
            for _, at, size in self.neighbours
        )

    def crowding(self, pose: Pose) -> list[str] | None:
        """The boxes a pose of the box comes closer to than the placement gap, or None if it
        reaches over an excluded region."""
        if any(overlaps_region(pose, self.size, region) for region in self.excluded):
            return None
        gap = self.parameters.placement_gap
        return [n for n, at, size in self.neighbours if boxes_overlap(pose, self.size, at, size, gap)]

    def packed_placements(self, rng: np.random.Generator) -> list[Placement]:
        """The packed poses of the box in the region that are clear of the boxes there."""
        gap = self.parameters.placement_gap
        footprints = [
            *(box_footprint(self.region, at, size, gap) for _, at, size in self.neighbours),
            *(region_footprint(self.region, region) for region in self.excluded),
        ]
        faces = [face for face, probability in self.preferred if probability > 0.0] or ALL_FACES
        candidates = packed_placements(self.region, self.size, faces, footprints, rng)
        return [p for p in candidates if self.crowding(p.world_from_box) == []]

    def segments(
        self, placement: Placement, rng: np.random.Generator, rejections: Rejections
    ) -> tuple[Segment, ...] | None:
        """Descend, release and retreat for one placement, or None if infeasible."""
        kitchen, parameters = self.kitchen, self.parameters
        world_from_tool = placement.world_from_box @ self.box_from_tool
        approach = world_from_tool.rotation[:, 2]
        if approach[2] > 0.1:
            return None
        q_place = kitchen.collision_free_ik(
            world_from_tool, self.descent_checker, rng, parameters.ik_solutions,
            rejected=lambda q: rejections.collided(self.descent_checker, q),
        )
        if q_place is None:
            return None
        bottom = self.region.top_z
        height = max(parameters.lift_height, self.region.ceiling_z + parameters.wall_clearance - bottom)
        descent = straight_approach(kitchen, q_place, world_from_tool, -UP, height, parameters)
        if descent is None or not all_valid(self.descent_checker, descent, rejections):
            return None
        if not self.clear_checker.is_valid(descent[0])[0]:
            rejections.collided(self.clear_checker, descent[0])
            return None
        retreat = straight_move(
            kitchen, q_place, world_from_tool, -parameters.pregrasp_distance * approach, parameters
        )
        if retreat is None:
            return None
        touching, clear = _released_checkers(
            kitchen, self.box, q_place, parameters.free_space_clearance, self.descent_checker.kept
        )
        if not all_valid(touching, retreat, rejections) or not all_valid(clear, retreat[-1:], rejections):
            return None
        release_qs, release_widths = hold_still(q_place, (self.width, self.open_width))
        segments = (
            Segment("descend", descent, np.full(len(descent), self.width)),
            Segment("release", release_qs, release_widths),
            Segment("retreat", retreat, np.full(len(retreat), self.open_width)),
        )
        return None if first_problem(kitchen, self.action_text, self.action[1], segments) else segments

    def targets(self, segments: tuple[Segment, ...], samples_tried: int) -> SkillTargets:
        return SkillTargets(
            action=self.action,
            goal_configuration=segments[0].configurations[0],
            held_box=self.box,
            gripper_width=self.width,
            segments=segments,
            free_space_checker=self.carrying_checker,
            samples_tried=samples_tried,
        )

    def exhausted(self, attempts: int) -> str:
        return f"no reachable collision-free placement in {attempts} samples"


def _released_checkers(
    kitchen: KitchenScene, box: str, q_place: FloatArray, clearance: float, kept: tuple[KeptClearance, ...]
) -> tuple[PyBulletCollisionChecker, PyBulletCollisionChecker]:
    """(fingers may touch the box and keep the ``kept`` clearances, ``clearance`` kept from
    everything) checkers of the scene after letting go at ``q_place``."""
    robot = kitchen.robot
    with kitchen.scene.preserved():
        robot.set_configuration(q_place)
        kitchen.release(box)
        kitchen.set_gripper_open()
        touching = kitchen.collision_checker([kitchen.finger_contact(box)], kept=kept)
        return touching, kitchen.collision_checker(margin=clearance)


ALL_FACES = [(axis, sign) for axis in range(3) for sign in (-1, 1)]
"""Every face a box may be put down on."""

TARGET_ROLES = ("support", "drawer", "base")
"""The role that names where ``place`` / ``place_in`` / ``stack`` put the box."""


def sample_place(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    binding: ActionBinding,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> SkillTargets:
    """Targets for putting the held ``object`` on a surface or region (``place``), into an open
    drawer (``place_in``) or on the top face of a box (``stack``), clear of the boxes there.

    Stable poses are sampled in the target region (preferring the face that was
    down when picked, then the face that puts the hand above the box); each is kept only if it
    overlaps no box already there and the hand can
    hold the box there with the grasp it has, lower it straight from above the
    region (and a drawer's walls), open the fingers and back away, all without
    collision. When no sampled pose is free of the boxes there, the failure is ``full``.
    """
    text = action_text(action)
    box = binding.argument("object", action[1])
    target = next(t for role in TARGET_ROLES if (t := binding.argument(role, action[1])) is not None)
    assert box is not None  # a required role
    if kitchen.held_box() != box:
        raise SkillFailure(text, f"the hand does not hold {box}", FailureKind.PRECONDITION)
    if target in kitchen.map.openables and not kitchen.is_opened(target):
        raise SkillFailure(text, f"{target} is closed", FailureKind.PRECONDITION, region=target)
    robot = kitchen.robot
    body = kitchen.box(box)
    attachment = kitchen.scene.attachment_of(body)
    assert attachment is not None
    hand_from_box = attachment.parent_link_from_child
    box_from_tool = (robot.hand_from_tool().inverse() @ hand_from_box).inverse()
    hand_above = face_along(box_from_tool.rotation[:, 2])
    region = kitchen.region(target)
    centre_inset = 0.5 * min(region.half_size) if target in kitchen.boxes else None
    if not fits_somewhere(region, kitchen.box_size(box), centre_inset):
        detail = f"{box} fits {target} in no orientation"
        raise SkillFailure(text, detail, FailureKind.TOO_LARGE, region=target)
    problem = PlaceProblem(
        kitchen=kitchen,
        action=action,
        parameters=parameters,
        box=box,
        size=kitchen.box_size(box),
        region=region,
        preferred=(
            (down_face(body.base_pose()), parameters.keep_down_probability),
            (hand_above, parameters.hand_above_probability),
        ),
        centre_inset=centre_inset,
        neighbours=tuple(
            (name, kitchen.box(name).base_pose(), kitchen.box_size(name))
            for name in kitchen.boxes
            if name != box
        ),
        excluded=tuple(kitchen.region_region(r) for r in kitchen.map.regions_on(target)),
        box_from_tool=box_from_tool,
        width=robot.gripper_width(),
        q_now=kitchen.arm_configuration(),
        open_width=robot.max_gripper_width,
        carrying_checker=kitchen.collision_checker(),
        descent_checker=kitchen.collision_checker(
            kept=kitchen.clear_of_boxes((box, target), parameters.neighbour_clearance)
        ),
        clear_checker=kitchen.collision_checker(margin=parameters.free_space_clearance),
    )
    return sample_skill(problem, rng, parameters, Rejections(kitchen, (box,), target))
