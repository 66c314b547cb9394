"""What a skill hands to motion planning and replay: a free-space goal, then scripted
segments with explicit joint waypoints, and how the action changes the scene."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.kitchen_scene import KitchenScene
from kitchen_tamp.world import AllowedContact, FloatArray, PyBulletCollisionChecker


@dataclass(frozen=True, eq=False)
class Segment:
    """A scripted motion: joint waypoints with the gripper width (and drawer) at each.

    ``attached_box`` is carried by the hand for the whole segment: a replayer
    attaches it at the first waypoint (or releases what the hand holds if None)
    before moving. ``drawer_values`` is given when ``openable`` moves with the hand.
    """

    name: str
    configurations: FloatArray
    gripper_widths: FloatArray
    attached_box: str | None = None
    openable: str | None = None
    drawer_values: FloatArray | None = None
    allowed_contacts: tuple[AllowedContact, ...] = ()

    def __post_init__(self) -> None:
        n = len(self.configurations)
        if self.configurations.ndim != 2 or n < 2:
            raise ValueError(f"segment {self.name!r} needs at least two waypoints as an (n, dof) array")
        if self.gripper_widths.shape != (n,):
            raise ValueError(f"segment {self.name!r}: one gripper width per waypoint expected")
        if (self.drawer_values is None) != (self.openable is None):
            raise ValueError(f"segment {self.name!r}: drawer values need the openable's name")
        if self.drawer_values is not None and self.drawer_values.shape != (n,):
            raise ValueError(f"segment {self.name!r}: one drawer value per waypoint expected")

    def __len__(self) -> int:
        return len(self.configurations)


@dataclass(frozen=True, eq=False)
class SkillTargets:
    """Everything needed to carry out one grounded action without knowing the skill.

    Motion planning moves the arm from the current configuration to
    ``goal_configuration`` with ``free_space_checker`` (which carries
    ``held_box`` and sees the drawer as it is). The segments then run in order
    from ``goal_configuration`` to ``final_configuration``.
    """

    action: tuple[str, tuple[str, ...]]
    goal_configuration: FloatArray
    held_box: str | None
    gripper_width: float
    segments: tuple[Segment, ...]
    free_space_checker: PyBulletCollisionChecker
    samples_tried: int

    def __post_init__(self) -> None:
        if not self.segments:
            raise ValueError("a skill needs at least one scripted segment")
        if not np.allclose(self.segments[0].configurations[0], self.goal_configuration):
            raise ValueError("the first segment must start at the free-space goal")
        for before, after in zip(self.segments, self.segments[1:], strict=False):
            if not np.allclose(before.configurations[-1], after.configurations[0]):
                raise ValueError(f"segment {after.name!r} does not start where {before.name!r} ends")

    @property
    def final_configuration(self) -> FloatArray:
        """Where the arm is after the last segment."""
        return np.asarray(self.segments[-1].configurations[-1])

    @property
    def final_held_box(self) -> str | None:
        """What the hand carries after the action."""
        return self.segments[-1].attached_box

    @property
    def action_text(self) -> str:
        """The action as PDDL text, e.g. ``(pickUp spam countertop)``."""
        return action_text(self.action)

    def apply(self, kitchen: KitchenScene) -> None:
        """Put the scene in the state after the action (arm, gripper, boxes, drawer)."""
        kitchen.robot.set_configuration(self.goal_configuration)
        for segment in self.segments:
            enter_segment(kitchen, segment)
            set_waypoint(kitchen, segment, len(segment) - 1)


def enter_segment(kitchen: KitchenScene, segment: Segment) -> None:
    """Go to the segment's first waypoint and make the hand carry ``segment.attached_box``."""
    set_waypoint(kitchen, segment, 0)
    held = kitchen.held_box()
    if held != segment.attached_box:
        if held is not None:
            kitchen.release(held)
        if segment.attached_box is not None:
            kitchen.scene.detach(kitchen.box(segment.attached_box))
            kitchen.grasp(segment.attached_box)


def set_waypoint(kitchen: KitchenScene, segment: Segment, index: int, fraction: float = 0.0) -> None:
    """Arm, gripper and drawer at waypoint ``index`` of ``segment``, or ``fraction`` of the way
    from it to the next waypoint (carried boxes follow)."""

    def at(values: FloatArray) -> FloatArray:
        if fraction == 0.0:
            return np.asarray(values[index])
        return np.asarray(values[index] + fraction * (values[index + 1] - values[index]))

    if segment.openable is not None and segment.drawer_values is not None:
        kitchen.set_opening(segment.openable, float(at(segment.drawer_values)))
    kitchen.robot.set_gripper_width(float(at(segment.gripper_widths)))
    kitchen.robot.set_configuration(at(segment.configurations))


def action_text(action: tuple[str, tuple[str, ...]]) -> str:
    """An action as PDDL text, e.g. ``(pickUp spam countertop)``."""
    name, args = action
    return "(" + " ".join((name, *args)) + ")"
