"""One execution under physics in progress: the arm driven along the trajectory, the grip
commanded as the kinematic judge read the plan, and what is observed along the way.

Per simulated tick the arm is commanded the time law's configuration; the
fingers the planned width, pressing ``grip_squeeze`` narrower only where the
judge's track says they hold something (so a planned release is a release, and
a planned opening a few millimetres wider than a box lets go of it). Observed:
each joint's lag behind its command, every contact of the robot with the
kitchen or a box that the action does not mean (``intended_contacts``, the same
policy as the kinematic judge's), and the slip of a held box in the hand.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from kitchen_tamp.execute.atom_comparison import state_mismatch
from kitchen_tamp.execute.physics.time_law import strokes
from kitchen_tamp.execute.physics.verdict import ActionFigures, PhysicsExecution, pose_errors
from kitchen_tamp.execute.verification import StepOutcome
from kitchen_tamp.kitchen import KitchenScene, Segment, SegmentTrack, abstract_state
from kitchen_tamp.kitchen.contact_policy import intended_contacts
from kitchen_tamp.kitchen.trajectory import ActionTrajectory
from kitchen_tamp.planning import Atom
from kitchen_tamp.world import AllowedContact, Pose
from kitchen_tamp.world.physics import PhysicsWorld

FrameCallback = Callable[[float, KitchenScene], None]
"""``on_frame(time_s, kitchen)``: called at simulated times ``frame_interval_s`` apart."""

SLIP_CHECK_TICKS = 12
"""A held box's slip in the hand is measured every this many ticks."""


class Rollout:
    """One physics execution in progress: the world, the clock and what has been observed."""

    def __init__(
        self,
        kitchen: KitchenScene,
        world: PhysicsWorld,
        result: PhysicsExecution,
        objects: dict[str, str],
        on_frame: FrameCallback | None,
    ) -> None:
        self.kitchen = kitchen
        self.objects = objects
        self.world = world
        self.result = result
        self.tolerances = result.configuration.tolerances
        self.on_frame = on_frame
        self.next_frame = 0.0
        self.hand = kitchen.robot.description.hand_link
        self.base_link = kitchen.robot.body.base_link_name
        self.gripped: str | None = None
        self.hand_from_gripped = Pose()
        self._reported: set[str] = set()

    # -- stepping ---------------------------------------------------------------------------------
    def step(self) -> None:
        self.world.step()
        if self.on_frame is not None and self.world.time >= self.next_frame - 1e-9:
            self.on_frame(self.world.time, self.kitchen)
            self.next_frame += self.result.configuration.frame_interval_s

    def scene_still(self) -> bool:
        limit = self.tolerances.still_speed
        for body in self.kitchen.boxes.values():
            linear, angular = self.world.body_speed(body)
            if linear > limit or 0.1 * angular > limit:
                return False
        return self.world.finger_speed() <= limit

    def settle(self) -> None:
        """Step until the boxes and fingers rest for a tenth of a second, or ``settle_s``."""
        steps = round(self.tolerances.settle_s / self.world.settings.time_step)
        needed = max(1, round(0.1 / self.world.settings.time_step))
        quiet = 0
        for _ in range(steps):
            self.step()
            quiet = quiet + 1 if self.scene_still() else 0
            if quiet >= needed:
                return

    def problem_once(self, kind: str, text: str) -> None:
        """Record ``text`` unless a problem of ``kind`` was recorded already."""
        if kind not in self._reported:
            self._reported.add(kind)
            self.result.problems.append(text)

    # -- the box in the hand ---------------------------------------------------------------------
    def hand_from_box(self, box: str) -> Pose:
        world_from_hand = self.kitchen.robot.body.link_pose(self.hand)
        return world_from_hand.inverse() @ self.kitchen.box(box).base_pose()

    def grip(self, box: str, label: str) -> None:
        if not self.world.holds(self.kitchen.box(box)):
            self.result.problems.append(f"{label}: the fingers closed without holding {box}")
            return
        self.gripped = box
        self.hand_from_gripped = self.hand_from_box(box)

    def measure_slip(self, figures: ActionFigures, label: str) -> None:
        if self.gripped is None:
            return
        slip_m, slip_rad = self.hand_from_box(self.gripped).distance_to(self.hand_from_gripped)
        figures.max_slip_m = max(figures.max_slip_m, slip_m)
        figures.max_slip_deg = max(figures.max_slip_deg, float(np.degrees(slip_rad)))
        if slip_m > self.tolerances.slip_m or np.degrees(slip_rad) > self.tolerances.slip_deg:
            box = self.gripped
            if not self.world.holds(self.kitchen.box(box)):
                self.result.problems.append(f"{label}: {box} fell out of the hand")
            else:
                self.result.problems.append(
                    f"{label}: {box} slipped {slip_m * 100:.1f} cm, {np.degrees(slip_rad):.0f} deg "
                    "in the hand"
                )
            self.gripped = None

    # -- what the robot touches and how well it follows -------------------------------------------
    def watch_contacts(self, figures: ActionFigures, label: str, intended: Sequence[AllowedContact]) -> None:
        for contact in self.world.robot_contacts(min_force=self.tolerances.contact_force_n):
            if contact.robot_link == self.base_link:
                continue
            if any(c.allows(contact.robot_link, contact.body, contact.link) for c in intended):
                continue
            figures.max_unplanned_force_n = max(figures.max_unplanned_force_n, contact.normal_force)
            pair = f"{contact.body}/{contact.link} and panda/{contact.robot_link}"
            worst = self.result.worst_unplanned_contact
            if worst is None or contact.normal_force > float(str(worst["force_n"])):
                self.result.worst_unplanned_contact = {
                    "where": label, "between": pair, "force_n": round(contact.normal_force, 3)
                }
            self.problem_once(f"contact {label}", f"{label}: unplanned contact between {pair} "
                              f"({contact.normal_force:.2f} N)")

    def watch_tracking(
        self, figures: ActionFigures, label: str, commanded: list[float], waypoint: int
    ) -> None:
        # seven joints a tick: plain floats (the same IEEE arithmetic as numpy's, without its overhead)
        positions = self.world.arm_positions()
        lag = [abs(now - wanted) for now, wanted in zip(positions, commanded, strict=True)]
        error = max(lag)
        figures.max_joint_error_rad = max(figures.max_joint_error_rad, error)
        if error > self.tolerances.tracking_rad:
            joint = self.kitchen.robot.description.arm_joints[lag.index(error)]
            self.problem_once(f"tracking {label}", f"{label}: after waypoint {waypoint} {joint} lags "
                              f"its command by {error:.3f} rad (bound {self.tolerances.tracking_rad} rad)")

    # -- one action -------------------------------------------------------------------------------
    def run_segment(
        self, segment: Segment, track: SegmentTrack, figures: ActionFigures, label: str,
        intended: Sequence[AllowedContact],
    ) -> None:
        world = self.world
        law = self.result.configuration.time_law
        for stroke in strokes(
            segment.configurations, segment.gripper_widths, world.arm_velocity_limits,
            2.0 * world.finger_velocity_limit, law,
        ):
            count = int(np.ceil(stroke.duration / world.settings.time_step))
            times = np.arange(1, count + 1, dtype=float) * world.settings.time_step
            qs, qds, widths = stroke.sample(times)
            intervals, fractions, _ = stroke.locate(times)
            intervals = stroke.first + intervals
            states = track.states_at(intervals, fractions)
            # the simulator takes Python floats: converted once a stroke, not once a tick
            ticks = zip(qs.tolist(), qds.tolist(), widths.tolist(), intervals.tolist(), states.tolist(),
                        strict=True)
            for tick, (q, qd, width, interval, state) in enumerate(ticks):
                if self.gripped is not None and track.carried[state] is None:  # the plan lets go here
                    self.measure_slip(figures, label)
                    self.gripped = None
                world.command_arm(q, qd)
                world.command_gripper(width, press=track.holds(state))
                self.step()
                self.watch_tracking(figures, label, q, interval)
                self.watch_contacts(figures, label, intended)
                if tick % SLIP_CHECK_TICKS == SLIP_CHECK_TICKS - 1:
                    self.measure_slip(figures, label)

    def run_action(
        self, index: int, step: ActionTrajectory, tracks: Sequence[SegmentTrack], outcome: StepOutcome
    ) -> ActionFigures:
        figures = ActionFigures(step.action)
        intended = intended_contacts(self.kitchen, outcome.arguments)
        for segment, track in zip(step.segments, tracks, strict=True):
            label = f"step {index + 1} {step.action} {segment.name}"
            self.run_segment(segment, track, figures, label, intended)
            if np.ptp(segment.gripper_widths) > 0.0:
                self.settle()
            carried = track.carried[-1]
            if carried is not None and self.gripped is None:
                self.grip(carried.box, label)
        self.measure_slip(figures, f"step {index + 1} {step.action}")
        figures.held_box = self.gripped
        return figures

    # -- comparing with the plan -------------------------------------------------------------------
    def observed_atoms(self) -> frozenset[Atom]:
        """Ψ(scene) with the box both fingers touch counted as held."""
        robot = self.kitchen.robot
        held = next((n for n, b in self.kitchen.boxes.items() if self.world.holds(b)), None)
        scene = self.kitchen.scene
        if held is not None:
            scene.attach(self.kitchen.box(held), robot.body, self.hand)
        try:
            return abstract_state(self.kitchen, self.objects)
        finally:
            if held is not None:
                scene.detach(self.kitchen.box(held))

    def compare(self, figures: ActionFigures, outcome: StepOutcome, expected: frozenset[Atom]) -> list[str]:
        """Record how the scene differs from the judge's reading of the plan; Ψ mismatches are
        problems, and boxes or drawers beyond tolerance are returned (drift)."""
        label = f"after {figures.action}"
        figures.end_s = self.world.time
        drift: list[str] = []
        mismatch = state_mismatch(self.observed_atoms(), expected)
        figures.as_planned = mismatch is None
        if mismatch is not None:
            self.result.problems.append(f"{label}: {mismatch}")
        tolerances = self.tolerances
        for box, pose in sorted(outcome.box_poses.items()):
            if box == outcome.held_box:
                continue
            errors = pose_errors(pose, self.kitchen.box(box).base_pose())
            figures.box_errors[box] = errors
            if errors["tilt_deg"] > tolerances.tilt_deg:
                drift.append(f"{label}: {box} leans {errors['tilt_deg']:.0f} deg")
            if errors["position_error_m"] > tolerances.position_m:
                drift.append(
                    f"{label}: {box} is {errors['position_error_m'] * 100:.1f} cm from its planned pose"
                )
        for drawer, value in outcome.openings.items():
            figures.drawer_errors_m[drawer] = abs(self.kitchen.opening(drawer) - value)
            if figures.drawer_errors_m[drawer] > tolerances.position_m:
                drift.append(
                    f"{label}: {drawer} is open {self.kitchen.opening(drawer) * 100:.1f} cm, "
                    f"planned {value * 100:.1f} cm"
                )
        return drift
