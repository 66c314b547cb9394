"""One action replayed as the judge sees it: what rides with the hand, where the drawer is,
what stands on what, and whether any state along the way collides -- all derived from the
action, the kitchen and the geometry, never from what a planner claims.

First every waypoint of a segment is checked against what the robot can do
(``kitchen_tamp.kitchen.robot_range``: the joints' ranges, the hand's opening).
Then, along the segment, at states ``resolution`` rad apart
(``kitchen_tamp.joint_spacing``):

- **attachment**: a box the action names rides with the hand from the state
  where the closing fingers hold it (``contact_policy.fingers_holding``) until
  the fingers open any wider than they held it, however little or slowly;
- **support**: whenever a box is let go of or taken, every loose box must stand
  on a region (``contact_policy.support_of``), or it would fall: the state is
  refused (in the drawer, a box rides with the drawer);
- **the drawer** the action names moves only while the fingers hold its
  handle, by as much as the hand moves along the drawer's axis; a hand that
  pulls it past its stop, or moves across the axis or turns while holding the
  handle, is refused;
- **collisions**: every pair of ``kitchen_tamp.world.collision.checked_pairs`` with the
  action's intended contacts (``contact_policy.intended_contacts``) allowed to
  ``CONTACT_PENETRATION_BOUND``; while the drawer moves, the boxes in it are
  checked against the cabinet too;
- fingers that close and hold nothing the action names are a problem.

The judge (``kitchen_tamp.execute.verification``) replays every action this way
and measures clearances (``world.collision.clearance_scan``: exact wherever the closest
approach or a collision can be); a planner replays the action it just sampled the same
way (``measure=False``: first problem only, the same measure up to the first
collision) and keeps the sample only if nothing is found, so a step it accepts is a
step the judge accepts.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Final

import numpy as np

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.kitchen.contact_policy import (
    CONTACT_PENETRATION_BOUND,
    finger_distance,
    fingers_holding,
    intended_contacts,
    support_of,
)
from kitchen_tamp.kitchen.replay_track import Carried, Gripped, SegmentTrack
from kitchen_tamp.kitchen.robot_range import clipped_to_range, range_problem
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment, SegmentSamples, interpolate_segment
from kitchen_tamp.read_only_mappings import read_only
from kitchen_tamp.world import FloatArray, PyBulletCollisionChecker

HANDLE_HOLD_ANGLE: Final = 0.02
"""Largest turn (rad) of the hand while it holds a handle: about the contact bound over the
fingers' pads (2 mm over 10 cm); the handle is a rigid bar on a straight slide."""


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
        self.where = label
        self.waypoint = 0
        self._took = False
        self._grip_faulted = False
        self.result = ActionReplay()

    def problem(self, text: str) -> None:
        self.result.problems.append(f"{self.where}: {text}")

    # -- what the fingers do ---------------------------------------------------------------------
    def _take_hold(self, width: float) -> bool:
        kitchen = self.kitchen
        held = fingers_holding(kitchen, self.boxes, self.drawers)
        if held is None:
            return False
        if held.kind == "box":
            kitchen.scene.detach(kitchen.box(held.name))
            kitchen.grasp(held.name)
            carried = _carried_now(kitchen)
            assert carried is not None
            self.carried = Carried(carried.box, carried.hand_from_box, width)
            self._check_support()
        else:
            self.gripped = Gripped(
                held.name, width, kitchen.robot.tool_pose(), kitchen.opening(held.name),
                pull_direction(kitchen, held.name),
            )
            self._grip_faulted = False
        return True

    def _closed_on_nothing(self) -> None:
        named = " or ".join([*self.boxes, *(f"the handle of {d}" for d in self.drawers)]) or "anything"
        nearest = [(finger_distance(self.kitchen, b), b) for b in self.boxes]
        hint = ""
        if nearest:
            distance, box = min(nearest)
            hint = f" ({box} is {distance * 1000:.0f} mm from the nearer finger)"
        self.problem(f"the fingers closed without holding {named}{hint}")

    def _check_support(self) -> None:
        """Every loose box stands on something (called where a box is let go of or taken)."""
        held = self.kitchen.held_box()
        for box in self.kitchen.boxes:
            if box != held and support_of(self.kitchen, box) is None:
                self.problem(f"{box} stands on nothing after waypoint {self.waypoint}: it would fall")

    def _advance(self, width: float, previous_width: float) -> None:
        """The events at a state the scene is posed in: the drawer follows a gripping hand,
        fingers opening past their grip let go, closing fingers take hold of what they hold."""
        self._took = False
        if self.gripped is not None:
            self._drag(self.gripped)
            if width < self.gripped.width:
                self.gripped = replace(self.gripped, width=width)
        if self.carried is not None and width < self.carried.width:
            self.carried = replace(self.carried, width=width)  # the grasp width is the narrowest
        if self.carried is not None and width > self.carried.width:
            self.kitchen.release(self.carried.box)
            self.carried = None
            self._check_support()
        if self.gripped is not None and width > self.gripped.width:
            self.gripped = None
        if width < previous_width and self.carried is None and self.gripped is None:
            self._took = self._take_hold(width)

    def _drag(self, gripped: Gripped) -> None:
        kitchen = self.kitchen
        world_from_tool = kitchen.robot.tool_pose()
        moved = world_from_tool.translation - gripped.world_from_tool.translation
        along = float(np.dot(moved, gripped.axis))
        across = float(np.linalg.norm(moved - along * gripped.axis))
        turned = gripped.world_from_tool.distance_to(world_from_tool)[1]
        lower, upper = kitchen.opening_limits(gripped.drawer)
        wanted = gripped.opening_start + along
        past = max(lower - wanted, wanted - upper)
        if not self._grip_faulted and past > CONTACT_PENETRATION_BOUND:
            self._grip_faulted = True
            self.problem(f"after waypoint {self.waypoint} the hand holding the handle of {gripped.drawer} "
                         f"pulls it {past * 100:.1f} cm past its stop")
        elif not self._grip_faulted and (across > CONTACT_PENETRATION_BOUND or turned > HANDLE_HOLD_ANGLE):
            self._grip_faulted = True
            self.problem(f"after waypoint {self.waypoint} the hand holding the handle of {gripped.drawer} "
                         f"moves {across * 1000:.1f} mm across the drawer's slide and turns "
                         f"{np.degrees(turned):.1f} deg (the handle cannot follow)")
        kitchen.set_opening(gripped.drawer, float(np.clip(wanted, lower, upper)))

    # -- one segment -------------------------------------------------------------------------------
    def segment(self, segment: Segment) -> None:
        robot = self.kitchen.robot
        self.where = f"{self.label} {segment.name}"
        out_of_range = range_problem(robot, segment)
        if out_of_range is not None:
            self.result.within_joint_limits = False
            self.problem(out_of_range)
            if not self.measure:
                return
            segment = clipped_to_range(robot, segment)
        samples = interpolate_segment(segment, self.resolution)
        self.result.configurations_checked += len(samples)
        track, runs = self._walk(segment, samples)
        self.result.tracks.append(track)
        for run in runs:
            if (not self._check(samples, track.openings, run) or self.result.problems) and not self.measure:
                return

    def _walk(self, segment: Segment, samples: SegmentSamples) -> tuple[SegmentTrack, list[_Run]]:
        """Pose the scene along the segment's states where anything may happen, recording what
        the judge derives per state and the runs of states one checker covers."""
        kitchen, robot = self.kitchen, self.kitchen.robot
        drawers = list(kitchen.map.openables)
        openings = {d: np.empty(len(samples)) for d in drawers}
        carried: list[Carried | None] = []
        gripped: list[str | None] = []
        runs: list[_Run] = []
        posed_width = previous_width = robot.gripper_width()
        closing = took = False
        key: tuple[float, int, str | None] | None = None
        for i in range(len(samples)):
            width = float(samples.gripper_widths[i])
            self.waypoint = int(samples.waypoint_of[i])
            # Nothing can change while the fingers keep their width and hold no handle: the
            # scene is posed only where something may happen (and at the segment's end).
            quiet = i > 0 and width == posed_width and self.gripped is None
            if not quiet:
                robot.set_gripper_width(width)
                robot.set_configuration(samples.configurations[i])
                self._advance(width, posed_width)
                posed_width = width
            if closing and width >= previous_width:
                if not took:
                    self._closed_on_nothing()
                closing = took = False
            if width < previous_width:
                closing = True
                took = took or self._took
            previous_width = width
            carried.append(self.carried)
            gripped.append(None if self.gripped is None else self.gripped.drawer)
            for drawer in drawers:
                openings[drawer][i] = openings[drawer][i - 1] if quiet else kitchen.opening(drawer)
            state = (width, id(self.carried), gripped[-1])
            if not quiet and state != key:
                if runs:
                    runs[-1].end = i
                runs.append(_Run(i, kitchen.collision_checker(self.contacts), state[2]))
                key = state
        robot.set_gripper_width(float(samples.gripper_widths[-1]))
        robot.set_configuration(samples.configurations[-1])
        if closing and not took:
            self._closed_on_nothing()
        runs[-1].end = len(samples)
        for values in openings.values():
            values.flags.writeable = False
        track = SegmentTrack(segment, samples, tuple(carried), tuple(gripped), read_only(openings))
        return track, runs

    def _check(self, samples: SegmentSamples, openings: Mapping[str, FloatArray], run: _Run) -> bool:
        """Check one run's states; record the closest approach and any collision."""
        rows = slice(run.start, run.end)
        qs = samples.configurations[rows]
        along = None
        if run.drawer is not None:
            joint = self.kitchen.map.openables[run.drawer].joint
            along = (self.kitchen.kitchen, [joint], openings[run.drawer][rows])
        if self.measure:  # measured where the lowest or a collision can be (exact there)
            found = run.checker.lowest_clearance(qs, max(self.result.min_clearance_m, 0.0), along=along)
            if found.value < self.result.min_clearance_m:
                self.result.min_clearance_m = found.value
                self.result.closest_approach = self.where
            first = found.first_collision
            depth = f" ({found.value * 1000:.1f} mm deep)"
        else:  # the same measure, up to the first collision
            first = run.checker.lowest_clearance(qs, 0.0, until_collision=True, along=along).first_collision
            depth = ""
        if first is None:
            return True
        at = None if along is None else (along[0], along[1], along[2][first : first + 1])
        pairs = ", ".join(f"{a}/{b}" for a, b in run.checker.colliding_pairs(qs[first], at))
        self.result.collision_free = False
        waypoint = int(samples.waypoint_of[run.start + first])
        self.problem(f"collision after waypoint {waypoint}{depth}{': ' + pairs if pairs else ''}")
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
