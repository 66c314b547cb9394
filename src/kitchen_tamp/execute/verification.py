"""Replay a trajectory in a freshly built kitchen and verify it, independently of the planner.

Checked: the trajectory starts at the arm's home and is continuous; every
segment is collision-free at states at most ``resolution`` rad apart (intended
contacts, e.g. fingers on the box being grasped, excepted) and within the joint
limits; after every action the scene's abstraction Ψ is the state the symbolic
plan predicts (so drawer opening and box poses are what the atoms say); at the
end Ψ entails the goal.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.execute.playback import SegmentSamples, interpolate_segment
from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.kitchen import KitchenScene, Segment, abstract_state, enter_segment, set_waypoint
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Atom, GroundAction, Task, atom_text


@dataclass
class Verification:
    """What the replay found; ``verified`` when every check passed."""

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

    @property
    def goal_reached(self) -> bool:
        return bool(self.goal_atoms) and all(self.goal_atoms.values())

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
            "min_clearance_m": round(self.min_clearance_m, 6),
            "closest_approach": self.closest_approach,
            "goal_atoms": dict(self.goal_atoms),
            "within_joint_limits": self.within_joint_limits,
            "continuous": self.continuous,
            "steps_as_planned": list(self.steps_as_planned),
            "final_atoms": list(self.final_atoms),
            "resolution_rad": self.resolution_rad,
            "configurations_checked": self.configurations_checked,
            "problems": list(self.problems),
        }


def parse_action(task: Task, text: str) -> GroundAction | None:
    """The task's ground action written as ``(name arg ...)``, or None."""
    words = text.strip().removeprefix("(").removesuffix(")").split()
    return task.action_named(words[0], words[1:]) if words else None


def _segment_clearances(kitchen: KitchenScene, segment: Segment, samples: SegmentSamples) -> np.ndarray:
    """Signed clearance (m) at each sample; one checker per gripper width, since the
    checker snapshots the fingers as they are."""
    clearances = np.empty(len(samples))
    for width in np.unique(samples.gripper_widths):
        rows = np.flatnonzero(samples.gripper_widths == width)
        with kitchen.scene.preserved():
            kitchen.robot.set_gripper_width(float(width))
            checker = kitchen.collision_checker(segment.allowed_contacts)
        qs = samples.configurations[rows]
        if segment.openable is not None and samples.drawer_values is not None:
            joint = kitchen.map.openables[segment.openable].joint
            clearances[rows] = checker.min_clearance_along(
                qs, kitchen.kitchen, [joint], samples.drawer_values[rows]
            )
        else:
            clearances[rows] = checker.min_clearance(qs)
    return clearances


def _check_segment(
    kitchen: KitchenScene, label: str, segment: Segment, resolution: float, result: Verification
) -> None:
    enter_segment(kitchen, segment)
    samples = interpolate_segment(segment, resolution)
    result.configurations_checked += len(samples)
    inside = [kitchen.robot.within_limits(q) for q in samples.configurations]
    if not all(inside):
        result.within_joint_limits = False
        result.problems.append(f"{label}: outside the joint limits at state {inside.index(False)}")
    clearances = _segment_clearances(kitchen, segment, samples)
    lowest = int(np.argmin(clearances))
    if clearances[lowest] < result.min_clearance_m:
        result.min_clearance_m = float(clearances[lowest])
        result.closest_approach = label
    if clearances[lowest] < 0.0:
        first = int(np.argmax(clearances < 0.0))
        result.collision_free = False
        checker = kitchen.collision_checker(segment.allowed_contacts)
        pairs = ", ".join(f"{a}/{b}" for a, b in checker.colliding_pairs(samples.configurations[first]))
        result.problems.append(
            f"{label}: collision after waypoint {int(samples.waypoint_of[first])} "
            f"({clearances[lowest] * 1000:.1f} mm deep){': ' + pairs if pairs else ''}"
        )
    set_waypoint(kitchen, segment, len(segment) - 1)


def _atoms_text(atoms: frozenset[Atom]) -> list[str]:
    return sorted(atom_text(a) for a in atoms)


def verify_trajectory(
    kitchen: KitchenScene,
    task: Task,
    trajectory: KitchenTrajectory,
    resolution: float = JUDGE_RESOLUTION_RAD,
    on_step: Callable[[int, str], None] | None = None,
) -> Verification:
    """Replay ``trajectory`` in ``kitchen`` (freshly built for ``task``) and check it.

    The scene is left in the final state. ``on_step(index, action)`` is called
    before each action (e.g. to wait for Enter).
    """
    result = Verification(resolution_rad=resolution)
    state = task.initial_state
    if trajectory.steps and not np.allclose(
        trajectory.steps[0].start, kitchen.arm_configuration(), atol=1e-6
    ):
        result.continuous = False
        result.problems.append("the trajectory does not start at the arm's home configuration")
    for index, step in enumerate(trajectory.steps):
        if on_step is not None:
            on_step(index, step.action)
        action = parse_action(task, step.action)
        if action is None:
            result.problems.append(f"step {index + 1} {step.action}: not an action of the task")
        elif not action.applicable(state):
            result.problems.append(f"step {index + 1} {step.action}: not applicable in the planned state")
        else:
            state = action.apply(state)
        for segment in step.segments:
            _check_segment(
                kitchen, f"step {index + 1} {step.action} {segment.name}", segment, resolution, result
            )
        observed = abstract_state(kitchen, task.objects)
        expected = task.state_atoms(state)
        result.steps_as_planned.append(observed == expected)
        if observed != expected:
            result.problems.append(
                f"step {index + 1} {step.action}: the scene shows {_atoms_text(observed - expected)} "
                f"but the plan expects {_atoms_text(expected - observed)}"
            )
    final = abstract_state(kitchen, task.objects)
    result.final_atoms = _atoms_text(final)
    result.goal_atoms = {atom_text(a): a in final for a in sorted(task.goal_atoms)}
    result.goal_atoms.update(
        {f"(not {atom_text(a)})": a not in final for a in sorted(task.negative_goal_atoms)}
    )
    return result
