"""A symbolic plan carried out in the kitchen: for each action, the arm's segments."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.world import FloatArray

FREE_SPACE_SEGMENT = "move"
"""Name of the planned free-space motion that starts every action's segments."""


@dataclass(frozen=True, eq=False)
class ActionTrajectory:
    """One action: a free-space move to the skill's goal, then the skill's scripted segments."""

    action: str
    segments: tuple[Segment, ...]

    def __post_init__(self) -> None:
        if not self.segments:
            raise ValueError(f"{self.action}: an action trajectory needs at least one segment")
        for before, after in zip(self.segments, self.segments[1:], strict=False):
            if not np.allclose(before.configurations[-1], after.configurations[0], atol=1e-9):
                raise ValueError(
                    f"{self.action}: segment {after.name!r} does not start where {before.name!r} ends"
                )

    @property
    def start(self) -> FloatArray:
        """The arm configuration the action starts from."""
        return np.asarray(self.segments[0].configurations[0])

    @property
    def end(self) -> FloatArray:
        """The arm configuration the action ends in."""
        return np.asarray(self.segments[-1].configurations[-1])

    @property
    def waypoint_count(self) -> int:
        """Waypoints over all segments."""
        return sum(len(s) for s in self.segments)


@dataclass(frozen=True, eq=False)
class KitchenTrajectory:
    """A whole refined plan, action after action, each starting where the last ended."""

    steps: tuple[ActionTrajectory, ...]

    def __post_init__(self) -> None:
        for before, after in zip(self.steps, self.steps[1:], strict=False):
            if not np.allclose(before.end, after.start, atol=1e-9):
                raise ValueError(f"{after.action} does not start where {before.action} ends")

    @property
    def plan(self) -> list[str]:
        """The actions as PDDL text."""
        return [step.action for step in self.steps]
