"""Replay a trajectory in a freshly built kitchen and verify it, independently of the planner.

The trajectory gives only what a planner decides: per action its text, per
segment arm configurations and gripper widths. Everything else is derived, per
action, by ``kitchen_tamp.kitchen.replay_action`` from the action, the kitchen
and the geometry: which box rides with the hand (from when the closing fingers
hold a box the action names until they open), where the drawer is (it follows
the hand only while the fingers hold its handle), and which contacts are
intended (only the action's own objects, each at most
``CONTACT_PENETRATION_BOUND`` deep).

Checked: the trajectory starts at the arm's home and is continuous; every
waypoint is within the joints' ranges and the hand's opening; every segment is
collision-free at states at most ``resolution`` rad apart, with every pair of
``kitchen_tamp.world.collision.checked_pairs`` checked (boxes riding the drawer against
the cabinet while it moves); a box let go of stands on something; a hand holding
a handle keeps to the drawer's slide and its travel; fingers never close on
nothing the action names; after every action the scene's abstraction Ψ is the
state the symbolic plan predicts; at the end Ψ entails the goal. Conditions
geometry does not show (``clean``, ``cooked``) are derived as the planner derives
them (``kitchen.record_conditions``): an action's condition effects hold when its
skill's requirement holds in the replayed scene (a ``process`` action's box rests
on its place).

What the judge derived is kept for the physics judge and for pictures: per step
the replayed tracks (per state what the hand holds, every drawer's opening) and
the scene after the step (``StepOutcome``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.execute.atom_comparison import all_hold, atoms_text, goal_literals, state_mismatch
from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.kitchen import (
    CONTACT_PENETRATION_BOUND,
    KitchenScene,
    SegmentTrack,
    abstract_state,
    record_conditions,
    replay_action,
)
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import GroundAction, Task
from kitchen_tamp.read_only_mappings import read_only
from kitchen_tamp.world import Pose


@dataclass(frozen=True, eq=False)
class StepOutcome:
    """One step as the judge read it: the action's arguments, and the scene after the step --
    every box's pose (the held one in the hand), the box in the hand, every drawer's opening."""

    arguments: tuple[str, ...]
    box_poses: Mapping[str, Pose]
    held_box: str | None
    openings: Mapping[str, float]


def step_outcome(kitchen: KitchenScene, arguments: tuple[str, ...]) -> StepOutcome:
    """The scene as it is now, as a ``StepOutcome`` of an action with ``arguments``."""
    return StepOutcome(
        arguments,
        read_only({name: body.base_pose() for name, body in kitchen.boxes.items()}),
        kitchen.held_box(),
        read_only({name: kitchen.opening(name) for name in kitchen.map.openables}),
    )


@dataclass
class Verification:
    """What the replay found; ``verified`` when every check passed. ``tracks`` are the
    replayed segments, step by step, with what the judge derived along them (for pictures)."""

    resolution_rad: float
    collision_free: bool = True
    within_joint_limits: bool = True
    continuous: bool = True
    min_clearance_m: float = float("inf")
    closest_approach: str = ""
    configurations_checked: int = 0
    steps_as_planned: list[bool] = field(default_factory=list)
    goal_atoms: dict[str, bool] = field(default_factory=dict)
    final_atoms: list[str] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)
    tracks: list[tuple[SegmentTrack, ...]] = field(default_factory=list)
    outcomes: list[StepOutcome] = field(default_factory=list)

    @property
    def goal_reached(self) -> bool:
        return all_hold(self.goal_atoms)

    @property
    def verified(self) -> bool:
        return (
            self.collision_free
            and self.within_joint_limits
            and self.continuous
            and all(self.steps_as_planned)
            and self.goal_reached
            and not self.problems
        )

    def report_data(self) -> dict[str, object]:
        """The ``verification`` section of a report."""
        return {
            "verified": self.verified,
            "collision_free": self.collision_free,
            "min_clearance_m": round(self.min_clearance_m, 6) if np.isfinite(self.min_clearance_m) else None,
            "closest_approach": self.closest_approach,
            "contact_penetration_bound_m": CONTACT_PENETRATION_BOUND,
            "goal_atoms": dict(self.goal_atoms),
            "within_joint_limits": self.within_joint_limits,
            "continuous": self.continuous,
            "steps_as_planned": list(self.steps_as_planned),
            "final_atoms": list(self.final_atoms),
            "resolution_rad": self.resolution_rad,
            "configurations_checked": self.configurations_checked,
            "problems": list(self.problems),
        }


def _words(text: str) -> list[str]:
    return text.strip().removeprefix("(").removesuffix(")").split()


def parse_action(task: Task, text: str) -> GroundAction | None:
    """The task's ground action written as ``(name arg ...)``, or None."""
    words = _words(text)
    return task.action_named(words[0], words[1:]) if words else None


JudgedStep = tuple[tuple[SegmentTrack, ...], StepOutcome]
"""One step as the judge read it: its replayed tracks and the scene after it."""


def judged_steps(verification: Verification) -> Iterator[JudgedStep]:
    """The steps of a finished verification, in order, as ``JudgedStep``s."""
    return zip(verification.tracks, verification.outcomes, strict=True)


class TrajectoryJudge:
    """The kinematic judge of one trajectory a step at a time, in ``kitchen`` (freshly built
    for ``task``): `judge` each step in order, then `finish` (``verify_trajectory`` does both
    for a whole trajectory; a planning run's judge follows the planner's steps as they come)."""

    def __init__(self, kitchen: KitchenScene, task: Task, resolution: float = JUDGE_RESOLUTION_RAD) -> None:
        self.kitchen, self.task = kitchen, task
        self.result = Verification(resolution_rad=resolution)
        self._home = kitchen.arm_configuration()
        self._state = task.initial_state

    @property
    def judged(self) -> int:
        """Steps judged so far."""
        return len(self.result.tracks)

    def judge(self, step: ActionTrajectory) -> JudgedStep:
        """Replay and check the next step; the scene is left after it."""
        result, task, kitchen = self.result, self.task, self.kitchen
        index = self.judged
        if index == 0 and not np.allclose(step.start, self._home, atol=1e-6):
            result.continuous = False
            result.problems.append("the trajectory does not start at the arm's home configuration")
        label = f"step {index + 1} {step.action}"
        action = parse_action(task, step.action)
        if action is None:
            result.problems.append(f"{label}: not an action of the task")
        elif not action.applicable(self._state):
            result.problems.append(f"{label}: not applicable in the planned state")
        else:
            self._state = action.apply(self._state)
        args = tuple(action.args) if action is not None else tuple(_words(step.action)[1:])
        replay = replay_action(kitchen, label, args, step.segments, result.resolution_rad, measure=True)
        result.tracks.append(tuple(replay.tracks))
        result.outcomes.append(step_outcome(kitchen, tuple(args)))
        result.problems += replay.problems
        result.configurations_checked += replay.configurations_checked
        result.collision_free &= replay.collision_free
        result.within_joint_limits &= replay.within_joint_limits
        if replay.min_clearance_m < result.min_clearance_m:
            result.min_clearance_m = replay.min_clearance_m
            result.closest_approach = replay.closest_approach
        condition_problem = None if action is None else record_conditions(kitchen, task, action)
        if condition_problem is not None:
            result.problems.append(f"{label}: {condition_problem}")
        observed = abstract_state(kitchen, task.objects)
        mismatch = state_mismatch(observed, task.state_atoms(self._state))
        result.steps_as_planned.append(mismatch is None)
        if mismatch is not None:
            result.problems.append(f"{label} {step.segments[-1].name} (its last segment): {mismatch}")
        return result.tracks[-1], result.outcomes[-1]

    def finish(self) -> Verification:
        """The verdict once every step was judged: the goal read off the scene as it is."""
        final = abstract_state(self.kitchen, self.task.objects)
        self.result.final_atoms = atoms_text(final)
        self.result.goal_atoms = goal_literals(self.task, final)
        return self.result


def verify_trajectory(
    kitchen: KitchenScene,
    task: Task,
    trajectory: KitchenTrajectory,
    resolution: float = JUDGE_RESOLUTION_RAD,
    on_step: Callable[[int, str], None] | None = None,
    on_judged: Callable[[ActionTrajectory, JudgedStep], None] | None = None,
) -> Verification:
    """Replay ``trajectory`` in ``kitchen`` (freshly built for ``task``) and check it.

    The scene is left in the final state. ``on_step(index, action)`` is called
    before each action (e.g. to wait for Enter), ``on_judged(step, judged)`` once the
    action's tracks and the scene after it are known (e.g. to execute it under
    physics meanwhile).
    """
    judge = TrajectoryJudge(kitchen, task, resolution)
    for index, step in enumerate(trajectory.steps):
        if on_step is not None:
            on_step(index, step.action)
        judged = judge.judge(step)
        if on_judged is not None:
            on_judged(step, judged)
    return judge.finish()
