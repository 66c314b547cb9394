"""What the plan says the scene should look like after each action, derived from the arm
configurations and gripper widths alone (the rest of a trajectory file is not trusted).

A box of a pick action becomes held where the fingers finish closing, at the
pose it had relative to the hand there; a box of a place action is let go where
the fingers start opening, at the pose the hand carried it to. A drawer of an
open action moves with the hand along its axis while the fingers are closed,
and the boxes planned inside it move with it. Physics execution compares the
simulated scene with these poses.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.execute.verification import parse_action
from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.kitchen.action_replay import pull_direction
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task
from kitchen_tamp.world import FloatArray, Pose

WIDTH_CHANGE = 1e-6
"""Gripper width changes (m) smaller than this are no change."""


@dataclass(frozen=True)
class GripEvent:
    """Where in an action the fingers finish closing or start opening."""

    segment: int
    waypoint: int
    closing: bool


@dataclass(frozen=True, eq=False)
class PlannedOutcome:
    """The scene after one action as planned: where each box is (the held one in the hand),
    which box the hand holds, and each drawer's joint value."""

    box_poses: dict[str, Pose]
    held_box: str | None
    openings: dict[str, float]
    grip_events: tuple[GripEvent, ...] = field(default=())


def grip_events(widths_per_segment: list[FloatArray]) -> tuple[GripEvent, ...]:
    """Every waypoint where the fingers finish closing or start opening, in order."""
    events = []
    for index, widths in enumerate(widths_per_segment):
        change = np.diff(widths)
        for i, delta in enumerate(change):
            if delta < -WIDTH_CHANGE and (i + 1 == len(change) or change[i + 1] >= -WIDTH_CHANGE):
                events.append(GripEvent(index, i + 1, closing=True))
            if delta > WIDTH_CHANGE and (i == 0 or change[i - 1] <= WIDTH_CHANGE):
                events.append(GripEvent(index, i, closing=False))
    return tuple(events)


def planned_outcomes(
    kitchen: KitchenScene, task: Task, trajectory: KitchenTrajectory
) -> list[PlannedOutcome]:
    """The planned scene after every action of ``trajectory``, starting from ``kitchen`` as
    built for ``task`` (forward kinematics only: the scene is left as it was)."""
    robot = kitchen.robot
    hand = robot.description.hand_link
    poses = {name: body.base_pose() for name, body in kitchen.boxes.items()}
    openings = {name: kitchen.opening(name) for name in kitchen.map.openables}
    directions = {name: pull_direction(kitchen, name) for name in kitchen.map.openables}
    held: str | None = None
    hand_from_box = Pose()
    outcomes = []
    state = task.initial_state
    for step in trajectory.steps:
        action = parse_action(task, step.action)
        arguments = action.args if action is not None else ()
        boxes = [a for a in arguments if a in kitchen.boxes]
        drawers = [a for a in arguments if a in kitchen.map.openables]
        events = grip_events([s.gripper_widths for s in step.segments])
        gripped_at: FloatArray | None = None
        for event in events:
            q = step.segments[event.segment].configurations[event.waypoint]
            world_from_hand = robot.forward_kinematics(q, hand)
            if event.closing and held is None and boxes:
                held = boxes[0]
                hand_from_box = world_from_hand.inverse() @ poses[held]
            elif event.closing and drawers:
                gripped_at = world_from_hand.translation
            elif not event.closing and held is not None:
                poses[held] = world_from_hand @ hand_from_box
                held = None
            elif not event.closing and gripped_at is not None:
                drawer = drawers[0]
                lower, upper = kitchen.opening_limits(drawer)
                moved = float(np.dot(world_from_hand.translation - gripped_at, directions[drawer]))
                new_opening = float(np.clip(openings[drawer] + moved, lower, upper))
                shift = (new_opening - openings[drawer]) * directions[drawer]
                atoms = task.state_atoms(state)
                for box in poses:
                    if ("boxIn", box, drawer) in atoms:
                        poses[box] = poses[box].translated(shift)
                openings[drawer] = new_opening
                gripped_at = None
        if held is not None:
            last = step.segments[-1].configurations[-1]
            poses[held] = robot.forward_kinematics(last, hand) @ hand_from_box
        if action is not None and action.applicable(state):
            state = action.apply(state)
        outcomes.append(PlannedOutcome(dict(poses), held, dict(openings), events))
    return outcomes
