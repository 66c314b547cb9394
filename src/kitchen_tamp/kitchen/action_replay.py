"""One action replayed as the judge sees it: what rides with the hand, where the drawer is,
and whether any state along the way collides -- all derived from the action, the kitchen
and the geometry, never from what a planner claims.

Along every segment, at states ``resolution`` rad apart (``kitchen_tamp.joint_spacing``):

- **attachment**: a box the action names rides with the hand from the state
  where the closing fingers hold it (``contact_policy.fingers_holding``) until
  the fingers open wider than they held it; released, it stays where it is (in
  the drawer, it rides with the drawer);
- **the drawer** the action names moves only while the closed fingers hold its
  handle, by as much as the hand moves along the drawer's axis (clamped to the
  joint's travel), and stops when they open;
- **collisions**: every pair of ``kitchen_tamp.world.checked_pairs`` with the
  action's intended contacts (``contact_policy.intended_contacts``) allowed to
  ``CONTACT_PENETRATION_BOUND``; while the drawer moves, the boxes in it are
  checked against the cabinet too;
- fingers that close and hold nothing the action names are a problem.

The judge (``kitchen_tamp.execute.verification``) replays every action this way
and measures clearances; a planner replays the action it just sampled the same
way (``measure=False``: first problem only, validity instead of clearance) and
keeps the sample only if nothing is found, so a step it accepts is a step the
judge accepts.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Final

import numpy as np

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.kitchen.contact_policy import finger_distance, fingers_holding, intended_contacts
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment, SegmentSamples, interpolate_segment
from kitchen_tamp.world import FloatArray, Pose, PyBulletCollisionChecker

OPEN_TOLERANCE: Final = 1e-6
"""The fingers let go when they are this much (m) wider than when they took hold."""


@dataclass(frozen=True)
class Carried:
    """A box riding with the hand at ``hand_from_box``, taken with the fingers ``width`` apart."""

    box: str
    hand_from_box: Pose
    width: float


@dataclass(frozen=True)
class Gripped:
    """A drawer held by its handle since the hand was at ``hand_start`` and it at ``opening_start``."""

    drawer: str
    width: float
    hand_start: FloatArray
    opening_start: float
    axis: FloatArray


@dataclass(frozen=True, eq=False)
class SegmentTrack:
    """One segment as replayed: its states and, per state, the box riding with the hand and
    every drawer's opening."""

    segment: Segment
    samples: SegmentSamples
    carried: tuple[Carried | None, ...]
    openings: Mapping[str, FloatArray]

    def __len__(self) -> int:
        return len(self.samples)

    def pose(self, kitchen: KitchenScene, index: int) -> None:
        """Put ``kitchen`` (replayed up to the state before) in state ``index``."""
        for drawer, values in self.openings.items():
            if kitchen.opening(drawer) != float(values[index]):
                kitchen.set_opening(drawer, float(values[index]))
        kitchen.robot.set_gripper_width(float(self.samples.gripper_widths[index]))
        kitchen.robot.set_configuration(self.samples.configurations[index])
        wanted, held = self.carried[index], kitchen.held_box()
        if held is not None and (wanted is None or wanted.box != held):
            kitchen.release(held)
        if wanted is not None and held != wanted.box:
            take(kitchen, wanted)


def take(kitchen: KitchenScene, carried: Carried) -> None:
    """Make ``carried.box`` ride with the hand at its pose relative to the hand."""
    body = kitchen.box(carried.box)
    kitchen.scene.detach(body)
    world_from_hand = kitchen.robot.body.link_pose(kitchen.robot.description.hand_link)
    kitchen.scene.set_base_pose(body, world_from_hand @ carried.hand_from_box)
    kitchen.grasp(carried.box)


def pull_direction(kitchen: KitchenScene, drawer: str) -> FloatArray:
    """World direction the drawer moves in as its joint value grows (from kinematics)."""
    link = kitchen.map.openables[drawer].link
    lower, upper = kitchen.opening_limits(drawer)
    with kitchen.scene.preserved():
        kitchen.set_opening(drawer, lower)
        closed = kitchen.kitchen.link_pose(link).translation
        kitchen.set_opening(drawer, upper)
        opened = kitchen.kitchen.link_pose(link).translation
    direction = opened - closed
    return np.asarray(direction / np.linalg.norm(direction))


@dataclass
class ActionReplay:
    """What replaying one action found."""

    tracks: list[SegmentTrack] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)
    min_clearance_m: float = float("inf")
    closest_approach: str = ""
    configurations_checked: int = 0
    collision_free: bool = True
    within_joint_limits: bool = True


def _carried_now(kitchen: KitchenScene) -> Carried | None:
    held = kitchen.held_box()
    if held is None:
        return None
    attachment = kitchen.scene.attachment_of(kitchen.box(held))
    assert attachment is not None
    return Carried(held, attachment.parent_link_from_child, kitchen.robot.gripper_width())


def _hand_position(kitchen: KitchenScene) -> FloatArray:
    return np.asarray(kitchen.robot.body.link_pose(kitchen.robot.description.hand_link).translation)


@dataclass
class _Run:
    """Consecutive states checked with one checker (same fingers, load and drawer hold)."""

    start: int
    checker: PyBulletCollisionChecker
    drawer: str | None
    end: int = 0


class _Replayer:
    """The replay of one action, segment after segment, on the live scene."""

    def __init__(
        self, kitchen: KitchenScene, label: str, args: Sequence[str], resolution: float, measure: bool
    ) -> None:
        self.kitchen = kitchen
        self.label = label
        self.resolution = resolution
        self.measure = measure
        self.boxes = [a for a in args if a in kitchen.boxes]
        self.drawers = [a for a in args if a in kitchen.map.openables]
        self.contacts = intended_contacts(kitchen, args)
        self.carried = _carried_now(kitchen)
        self.gripped: Gripped | None = None
        self._took = False
        self.result = ActionReplay()

    def _take_hold(self) -> bool:
        kitchen = self.kitchen
        held = fingers_holding(kitchen, self.boxes, self.drawers)
        if held is None:
            return False
        width = kitchen.robot.gripper_width()
        if held.kind == "box":
            kitchen.scene.detach(kitchen.box(held.name))
            kitchen.grasp(held.name)
            self.carried = _carried_now(kitchen)
        else:
            self.gripped = Gripped(
                held.name,
                width,
                _hand_position(kitchen),
                kitchen.opening(held.name),
                pull_direction(kitchen, held.name),
            )
        return True

    def _closed_on_nothing(self, where: str) -> None:
        named = " or ".join([*self.boxes, *(f"the handle of {d}" for d in self.drawers)]) or "anything"
        nearest = [(finger_distance(self.kitchen, b), b) for b in self.boxes]
        hint = ""
        if nearest:
            distance, box = min(nearest)
            hint = f" ({box} is {distance * 1000:.0f} mm from the nearer finger)"
        self.result.problems.append(f"{where}: the fingers closed without holding {named}{hint}")

    def segment(self, segment: Segment) -> None:
        kitchen, robot = self.kitchen, self.kitchen.robot
        where = f"{self.label} {segment.name}"
        samples = interpolate_segment(segment, self.resolution)
        self.result.configurations_checked += len(samples)
        outside = ~np.all(
            (samples.configurations >= robot.lower - 1e-9) & (samples.configurations <= robot.upper + 1e-9),
            axis=1,
        )
        if outside.any():
            self.result.within_joint_limits = False
            self.result.problems.append(
                f"{where}: outside the joint limits at state {int(np.argmax(outside))}"
            )
            if not self.measure:
                return
        drawers = list(kitchen.map.openables)
        openings = {d: np.empty(len(samples)) for d in drawers}
        carried: list[Carried | None] = []
        runs: list[_Run] = []
        previous_width = robot.gripper_width()
        closing = took = False
        key: tuple[float, int, str | None] | None = None
        for i in range(len(samples)):
            width = float(samples.gripper_widths[i])
            # Nothing can change while the fingers keep their width and hold no handle: the
            # scene is posed only where something may happen (and at the segment's end).
            quiet = i > 0 and abs(width - previous_width) <= OPEN_TOLERANCE and self.gripped is None
            if not quiet:
                robot.set_gripper_width(width)
                robot.set_configuration(samples.configurations[i])
                self._advance(width, previous_width)
            if closing and width >= previous_width - OPEN_TOLERANCE:
                if not took:
                    self._closed_on_nothing(where)
                closing = took = False
            if width < previous_width - OPEN_TOLERANCE:
                closing = True
                took = took or self._took
            previous_width = width
            carried.append(self.carried)
            for drawer in drawers:
                openings[drawer][i] = openings[drawer][i - 1] if quiet else kitchen.opening(drawer)
            state = (width, id(self.carried), None if self.gripped is None else self.gripped.drawer)
            if not quiet and state != key:
                if runs:
                    runs[-1].end = i
                runs.append(_Run(i, kitchen.collision_checker(self.contacts), state[2]))
                key = state
        robot.set_gripper_width(float(samples.gripper_widths[-1]))
        robot.set_configuration(samples.configurations[-1])
        if closing and not took:
            self._closed_on_nothing(where)
        runs[-1].end = len(samples)
        for values in openings.values():
            values.flags.writeable = False
        self.result.tracks.append(SegmentTrack(segment, samples, tuple(carried), MappingProxyType(openings)))
        for run in runs:
            if not self._check(where, samples, openings, run) and not self.measure:
                return

    def _advance(self, width: float, previous_width: float) -> None:
        """The events at a state the scene is posed in: the drawer follows a gripping hand,
        opening fingers let go, closing fingers take hold of what they hold (``_took``)."""
        kitchen = self.kitchen
        self._took = False
        if self.gripped is not None:
            self._drag(self.gripped)
        if self.carried is not None and width > self.carried.width + OPEN_TOLERANCE:
            kitchen.release(self.carried.box)
            self.carried = None
        if self.gripped is not None and width > self.gripped.width + OPEN_TOLERANCE:
            self.gripped = None
        if width < previous_width - OPEN_TOLERANCE and self.carried is None and self.gripped is None:
            self._took = self._take_hold()

    def _drag(self, gripped: Gripped) -> None:
        kitchen = self.kitchen
        moved = float(np.dot(_hand_position(kitchen) - gripped.hand_start, gripped.axis))
        lower, upper = kitchen.opening_limits(gripped.drawer)
        kitchen.set_opening(gripped.drawer, float(np.clip(gripped.opening_start + moved, lower, upper)))

    def _check(
        self, where: str, samples: SegmentSamples, openings: Mapping[str, FloatArray], run: _Run
    ) -> bool:
        """Check one run's states; record the closest approach and any collision."""
        rows = slice(run.start, run.end)
        qs = samples.configurations[rows]
        along = None
        if run.drawer is not None:
            joint = self.kitchen.map.openables[run.drawer].joint
            along = (self.kitchen.kitchen, [joint], openings[run.drawer][rows])
        if self.measure:
            if along is None:
                clearances = run.checker.min_clearance(qs)
            else:
                clearances = run.checker.min_clearance_along(qs, *along)
            lowest = int(np.argmin(clearances))
            if clearances[lowest] < self.result.min_clearance_m:
                self.result.min_clearance_m = float(clearances[lowest])
                self.result.closest_approach = where
            bad = clearances < 0.0
            depth = f" ({float(clearances[lowest]) * 1000:.1f} mm deep)"
        else:
            valid = run.checker.is_valid(qs) if along is None else run.checker.is_valid_along(qs, *along)
            bad = ~valid
            depth = ""
        if not bad.any():
            return True
        first = int(np.argmax(bad))
        at = None if along is None else (along[0], along[1], along[2][first : first + 1])
        pairs = ", ".join(f"{a}/{b}" for a, b in run.checker.colliding_pairs(qs[first], at))
        self.result.collision_free = False
        waypoint = int(samples.waypoint_of[run.start + first])
        self.result.problems.append(
            f"{where}: collision after waypoint {waypoint}{depth}{': ' + pairs if pairs else ''}"
        )
        return False


def replay_action(
    kitchen: KitchenScene,
    label: str,
    args: Sequence[str],
    segments: Sequence[Segment],
    resolution: float = JUDGE_RESOLUTION_RAD,
    measure: bool = True,
) -> ActionReplay:
    """Replay the segments of an action with arguments ``args`` from the scene as it is, and
    leave the scene in the state they lead to. ``label`` (e.g. ``step 2 (pickUp sugar
    stove)``) starts every problem, followed by the segment's name. With ``measure`` every
    state's clearance is measured; without, checking stops at the first problem."""
    replayer = _Replayer(kitchen, label, args, resolution, measure)
    for segment in segments:
        replayer.segment(segment)
        if replayer.result.problems and not measure:
            break
    return replayer.result


def first_problem(
    kitchen: KitchenScene, label: str, args: Sequence[str], segments: Sequence[Segment]
) -> str | None:
    """The first problem the judge would find replaying ``segments`` from their first state
    (the rest of the scene as it is now), or None; the scene is left as it was."""
    with kitchen.scene.preserved():
        kitchen.robot.set_gripper_width(float(segments[0].gripper_widths[0]))
        kitchen.robot.set_configuration(segments[0].configurations[0])
        found = replay_action(kitchen, label, args, segments, measure=False)
    return found.problems[0] if found.problems else None
