"""What a skill hands to motion planning: a free-space goal, then scripted segments with
explicit joint waypoints and gripper widths (what they do to the scene is derived by
``action_replay``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.action_replay import replay_action
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.planning import atom_text
from kitchen_tamp.world import FloatArray, PyBulletCollisionChecker


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
    def action_text(self) -> str:
        """The action as PDDL text, e.g. ``(pickUp spam countertop)``."""
        return action_text(self.action)

    def apply(self, kitchen: KitchenScene) -> None:
        """Put the scene in the state the segments lead to from the free-space goal, as the
        judge derives it (arm, gripper, what the hand holds, the drawer)."""
        kitchen.robot.set_configuration(self.goal_configuration)
        replay_action(kitchen, self.action_text, self.action[1], self.segments, measure=False)


def action_text(action: tuple[str, tuple[str, ...]]) -> str:
    """An action as PDDL text, e.g. ``(pickUp spam countertop)``."""
    name, args = action
    return atom_text((name, *args))
