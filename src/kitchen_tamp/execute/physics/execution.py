"""Execution under physics: run a trajectory in a fresh simulated kitchen and compare the
scene with the plan after every action.

The arm follows the trajectory's configurations on a time law within its
velocity limits, under position control; the fingers close tighter than the
planned width with a bounded force, so a box is held by friction and nothing
else, and a drawer moves only because the hand pulls its handle. After each
action the scene settles; then Ψ(scene) must be the planned state, and every box
must lie within the tolerances of its planned pose (position and tilt: Ψ alone
would call a box leaning 30 degrees "on" the surface it leans on). Only each
action's text and each segment's configurations and gripper widths are used.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.execute.atom_comparison import all_hold, atoms_text, goal_literals, state_mismatch
from kitchen_tamp.execute.physics.plan import PlannedOutcome, planned_outcomes
from kitchen_tamp.execute.physics.replanning import Replanner, replan_rest
from kitchen_tamp.execute.physics.time_law import DEFAULT_TIME_LAW, TimeLaw, strokes
from kitchen_tamp.execute.run_report import RunReport
from kitchen_tamp.execute.verification import parse_action
from kitchen_tamp.kitchen import KitchenMap, KitchenScene, abstract_state, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Atom, Task
from kitchen_tamp.world import Pose
from kitchen_tamp.world.physics import DEFAULT_PHYSICS, PhysicsSettings, PhysicsWorld

FrameCallback = Callable[[float, KitchenScene], None]
"""``on_frame(time_s, kitchen)``: called at simulated times ``frame_interval_s`` apart."""


@dataclass(frozen=True)
class PhysicsTolerances:
    """How far the simulated scene may be from the plan, and how long it may take to settle."""

    position_m: float = 0.02
    tilt_deg: float = 10.0
    slip_m: float = 0.02
    slip_deg: float = 10.0
    still_speed: float = 0.002
    """A body moving slower than this (m/s, and rad/s x 0.1 m) counts as still."""
    settle_s: float = 1.0
    """Longest wait for the scene to come to rest after an action or a gripper change."""


DEFAULT_TOLERANCES = PhysicsTolerances()


@dataclass
class ActionFigures:
    """What one action did under physics."""

    action: str
    max_joint_error_rad: float = 0.0
    held_box: str | None = None
    max_slip_m: float = 0.0
    max_slip_deg: float = 0.0
    as_planned: bool = True
    box_errors: dict[str, dict[str, float]] = field(default_factory=dict)
    drawer_errors_m: dict[str, float] = field(default_factory=dict)
    end_s: float = 0.0
    """Simulated time when the scene was compared with the plan after the action."""

    def data(self) -> dict[str, object]:
        return {
            "action": self.action,
            "max_joint_error_rad": round(self.max_joint_error_rad, 5),
            "held_box": self.held_box,
            "max_slip_m": round(self.max_slip_m, 5),
            "max_slip_deg": round(self.max_slip_deg, 3),
            "as_planned": self.as_planned,
            "box_errors": self.box_errors,
            "drawer_errors_m": {k: round(v, 5) for k, v in self.drawer_errors_m.items()},
            "end_s": round(self.end_s, 4),
        }


@dataclass
class PhysicsExecution:
    """The verdict of execution under physics and the figures behind it."""

    settings: PhysicsSettings
    time_law: TimeLaw
    tolerances: PhysicsTolerances
    actions: list[ActionFigures] = field(default_factory=list)
    goal_atoms: dict[str, bool] = field(default_factory=dict)
    final_atoms: list[str] = field(default_factory=list)
    final_box_errors: dict[str, dict[str, float]] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)
    replans: list[dict[str, object]] = field(default_factory=list)
    simulated_s: float = 0.0

    @property
    def goal_reached(self) -> bool:
        return all_hold(self.goal_atoms)

    @property
    def verified(self) -> bool:
        return (
            len(self.actions) > 0
            and all(a.as_planned for a in self.actions)
            and self.goal_reached
            and not self.problems
        )

    def report_data(self) -> dict[str, object]:
        """The ``physics`` section of a report."""
        return {
            "verified": self.verified,
            "goal_atoms": dict(self.goal_atoms),
            "final_atoms": list(self.final_atoms),
            "final_box_errors": self.final_box_errors,
            "actions": [a.data() for a in self.actions],
            "problems": list(self.problems),
            "replans": list(self.replans),
            "simulated_s": round(self.simulated_s, 3),
            "tolerances": {
                "position_m": self.tolerances.position_m,
                "tilt_deg": self.tolerances.tilt_deg,
                "slip_m": self.tolerances.slip_m,
                "slip_deg": self.tolerances.slip_deg,
            },
            "settings": {
                "time_step_s": self.settings.time_step,
                "grip_force_n": self.settings.grip_force,
                "grip_squeeze_m": self.settings.grip_squeeze,
                "passive_joint_friction": self.settings.passive_joint_friction,
                "box_friction": self.settings.box_material.lateral,
                "speed_fraction": self.time_law.speed_fraction,
            },
        }


def pose_errors(planned: Pose, actual: Pose) -> dict[str, float]:
    """Position error (m), tilt (deg: angle between the planned and actual box up-axes as
    seen in the world) and whole rotation error (deg) of a box."""
    position, rotation = actual.distance_to(planned)
    up_planned = planned.rotation.T @ np.array([0.0, 0.0, 1.0])
    up_actual = actual.rotation.T @ np.array([0.0, 0.0, 1.0])
    tilt = float(np.degrees(np.arccos(np.clip(np.dot(up_planned, up_actual), -1.0, 1.0))))
    return {
        "position_error_m": round(position, 5),
        "tilt_deg": round(tilt, 3),
        "rotation_deg": round(float(np.degrees(rotation)), 3),
    }



class _Rollout:
    """One physics execution in progress: the world, the clock and what has been observed."""

    def __init__(
        self,
        kitchen: KitchenScene,
        world: PhysicsWorld,
        result: PhysicsExecution,
        objects: dict[str, str],
        on_frame: FrameCallback | None,
        frame_interval_s: float,
    ) -> None:
        self.kitchen = kitchen
        self.objects = objects
        self.world = world
        self.result = result
        self.on_frame = on_frame
        self.frame_interval_s = frame_interval_s
        self.next_frame = 0.0
        self.hand = kitchen.robot.description.hand_link
        self.gripped: str | None = None
        self.hand_from_gripped = Pose()

    # -- stepping ---------------------------------------------------------------------------------
    def step(self) -> None:
        self.world.step()
        if self.on_frame is not None and self.world.time >= self.next_frame - 1e-9:
            self.on_frame(self.world.time, self.kitchen)
            self.next_frame += self.frame_interval_s

    def scene_still(self) -> bool:
        limit = self.result.tolerances.still_speed
        for body in self.kitchen.boxes.values():
            linear, angular = self.world.body_speed(body)
            if linear > limit or 0.1 * angular > limit:
                return False
        return self.world.finger_speed() <= limit

    def settle(self) -> None:
        """Step until the boxes and fingers rest for a tenth of a second, or ``settle_s``."""
        steps = round(self.result.tolerances.settle_s / self.world.settings.time_step)
        needed = max(1, round(0.1 / self.world.settings.time_step))
        quiet = 0
        for _ in range(steps):
            self.step()
            quiet = quiet + 1 if self.scene_still() else 0
            if quiet >= needed:
                return

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
        tolerances = self.result.tolerances
        if slip_m > tolerances.slip_m or np.degrees(slip_rad) > tolerances.slip_deg:
            box = self.gripped
            if not self.world.holds(self.kitchen.box(box)):
                self.result.problems.append(f"{label}: {box} fell out of the hand")
            else:
                self.result.problems.append(
                    f"{label}: {box} slipped {slip_m * 100:.1f} cm, {np.degrees(slip_rad):.0f} deg "
                    "in the hand"
                )
            self.gripped = None

    # -- one action -------------------------------------------------------------------------------
    def run_action(self, index: int, step: ActionTrajectory, planned: PlannedOutcome) -> ActionFigures:
        figures = ActionFigures(step.action)
        world = self.world
        law = self.result.time_law
        for number, segment in enumerate(step.segments):
            label = f"step {index + 1} {step.action} {segment.name}"
            opening = [e for e in planned.grip_events if e.segment == number and not e.closing]
            if opening:
                self.measure_slip(figures, label)
                self.gripped = None
            for stroke in strokes(
                segment.configurations,
                segment.gripper_widths,
                world.arm_velocity_limits,
                2.0 * world.finger_velocity_limit,
                law,
            ):
                count = int(np.ceil(stroke.duration / world.settings.time_step))
                times = np.arange(1, count + 1, dtype=float) * world.settings.time_step
                qs, qds, widths = stroke.sample(times)
                for tick in range(count):
                    world.command_arm(qs[tick], qds[tick])
                    world.command_gripper(float(widths[tick]))
                    self.step()
                    actual, _ = world.arm_state()
                    error = float(np.max(np.abs(actual - qs[tick])))
                    figures.max_joint_error_rad = max(figures.max_joint_error_rad, error)
                    if tick % 12 == 11:
                        self.measure_slip(figures, label)
            if np.ptp(segment.gripper_widths) > 0.0:
                self.settle()
            closing = [e for e in planned.grip_events if e.segment == number and e.closing]
            box = planned.held_box
            if closing and box is not None and self.gripped is None:
                self.grip(box, label)
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

    def compare(
        self, figures: ActionFigures, planned: PlannedOutcome, expected: frozenset[Atom]
    ) -> list[str]:
        """Record how the scene differs from the plan; Ψ mismatches are problems, and boxes or
        drawers beyond tolerance are returned (the drift a re-plan may absorb)."""
        label = f"after {figures.action}"
        figures.end_s = self.world.time
        drift: list[str] = []
        observed = self.observed_atoms()
        mismatch = state_mismatch(observed, expected)
        figures.as_planned = mismatch is None
        if mismatch is not None:
            self.result.problems.append(f"{label}: {mismatch}")
        tolerances = self.result.tolerances
        for box, pose in sorted(planned.box_poses.items()):
            if box == planned.held_box:
                continue
            errors = pose_errors(pose, self.kitchen.box(box).base_pose())
            figures.box_errors[box] = errors
            if errors["tilt_deg"] > tolerances.tilt_deg:
                drift.append(f"{label}: {box} leans {errors['tilt_deg']:.0f} deg")
            if errors["position_error_m"] > tolerances.position_m:
                drift.append(
                    f"{label}: {box} is {errors['position_error_m'] * 100:.1f} cm from its planned pose"
                )
        for drawer, value in planned.openings.items():
            figures.drawer_errors_m[drawer] = abs(self.kitchen.opening(drawer) - value)
            if figures.drawer_errors_m[drawer] > tolerances.position_m:
                drift.append(
                    f"{label}: {drawer} is open {self.kitchen.opening(drawer) * 100:.1f} cm, "
                    f"planned {value * 100:.1f} cm"
                )
        return drift


def execute_under_physics(
    task: Task,
    trajectory: KitchenTrajectory,
    settings: PhysicsSettings = DEFAULT_PHYSICS,
    time_law: TimeLaw = DEFAULT_TIME_LAW,
    tolerances: PhysicsTolerances = DEFAULT_TOLERANCES,
    on_frame: FrameCallback | None = None,
    frame_interval_s: float = 1.0 / 30.0,
    replan: Replanner | None = None,
    max_replans: int = 2,
    kitchen_map: KitchenMap | None = None,
) -> PhysicsExecution:
    """Run ``trajectory`` in a fresh simulated kitchen for ``task`` and judge it.

    With ``replan``, a scene that has drifted beyond tolerance after an action (Ψ still as
    planned, hand empty) gets the rest of the plan refined again from where things are,
    up to ``max_replans`` times; each re-plan is reported."""
    result = PhysicsExecution(settings, time_law, tolerances)
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        steps = list(trajectory.steps)
        outcomes = planned_outcomes(kitchen, task, trajectory)
        world = PhysicsWorld(
            kitchen.scene, kitchen.robot, [kitchen.kitchen], list(kitchen.boxes.values()), settings
        )
        rollout = _Rollout(kitchen, world, result, dict(task.objects), on_frame, frame_interval_s)
        rollout.settle()
        state = task.initial_state
        index = 0
        while index < len(steps):
            step, planned = steps[index], outcomes[index]
            figures = rollout.run_action(index, step, planned)
            action = parse_action(task, step.action)
            if action is not None and action.applicable(state):
                state = action.apply(state)
            world.command_arm(step.end)
            rollout.settle()
            drift = rollout.compare(figures, planned, task.state_atoms(state))
            result.actions.append(figures)
            index += 1
            can_replan = replan is not None and len(result.replans) < max_replans and index < len(steps)
            if drift and can_replan and figures.as_planned and figures.held_box is None:
                assert replan is not None
                again = replan_rest(task, state, kitchen, replan)
                result.replans.append(
                    {
                        "after": step.action,
                        "reason": "; ".join(drift),
                        "plan": None if again is None else again.trajectory.plan,
                    }
                )
                if again is not None:
                    steps[index:] = again.trajectory.steps
                    outcomes[index:] = again.outcomes
                    continue
            result.problems.extend(drift)
        final = rollout.observed_atoms()
        result.final_atoms = atoms_text(final)
        result.goal_atoms = goal_literals(task, final)
        if result.actions:
            result.final_box_errors = result.actions[-1].box_errors
        result.simulated_s = world.time
    return result


def judge_under_physics(
    task: Task,
    trajectory: KitchenTrajectory,
    report: RunReport,
    on_frame: FrameCallback | None = None,
    replan: Replanner | None = None,
    kitchen_map: KitchenMap | None = None,
) -> PhysicsExecution:
    """Execute ``trajectory`` under physics (in the kitchen of ``kitchen_map``, the default one
    if None) and record the verdict in ``report``: its
    ``physics`` section, ``timing.physics_s`` and, if physics failed, the run's failure."""
    clock = time.perf_counter()
    execution = execute_under_physics(
        task, trajectory, on_frame=on_frame, replan=replan, kitchen_map=kitchen_map
    )
    report.timing["physics_s"] = time.perf_counter() - clock
    report.physics = execution.report_data()
    if not execution.verified:
        report.fail("physics", "; ".join(execution.problems[:3]) or "the goal does not hold under physics")
    return execution
