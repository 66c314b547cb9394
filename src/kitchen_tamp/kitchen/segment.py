"""A segment: what a planner decides for one stretch of an action -- joint waypoints and the
gripper opening at each -- and the states along it that a check visits.

A segment says nothing about what rides with the hand or where the drawer is:
the judge derives that from the action, the kitchen and the geometry
(``kitchen_tamp.kitchen.action_replay``). Its name is a label for people.

A segment's waypoints may be far apart (a free-space move is a few joint-space
corners); ``interpolate_segment`` fills them in so no two states are further
apart than a joint-space resolution (by the rule of ``kitchen_tamp.joint_spacing``)
and the gripper changes by no more than ``LINEAR_STEP`` between them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

import numpy as np

from kitchen_tamp.joint_spacing import interval_count
from kitchen_tamp.world import FloatArray

LINEAR_STEP: Final = 0.005
"""Largest change (m) of the gripper width between two interpolated states."""


@dataclass(frozen=True, eq=False)
class Segment:
    """A scripted or planned motion: joint waypoints with the gripper width at each."""

    name: str
    configurations: FloatArray
    gripper_widths: FloatArray

    def __post_init__(self) -> None:
        n = len(self.configurations)
        if self.configurations.ndim != 2 or n < 2:
            raise ValueError(f"segment {self.name!r} needs at least two waypoints as an (n, dof) array")
        if self.gripper_widths.shape != (n,):
            raise ValueError(f"segment {self.name!r}: one gripper width per waypoint expected")

    def __len__(self) -> int:
        return len(self.configurations)


@dataclass(frozen=True, eq=False)
class SegmentSamples:
    """States along a segment: arm configurations, gripper widths, and ``waypoint_of`` = the
    index of the waypoint each state lies after."""

    configurations: FloatArray
    gripper_widths: FloatArray
    waypoint_of: np.ndarray

    def __len__(self) -> int:
        return len(self.configurations)


def interpolate_segment(segment: Segment, joint_step: float) -> SegmentSamples:
    """Every waypoint, and between two waypoints evenly spaced states at most ``joint_step``
    apart by the rule of ``kitchen_tamp.joint_spacing``."""
    qs, widths = segment.configurations, segment.gripper_widths
    parts_q: list[FloatArray] = [qs[:1]]
    parts_w: list[FloatArray] = [widths[:1]]
    owners: list[np.ndarray] = [np.zeros(1, dtype=int)]
    for i in range(len(qs) - 1):
        linear = abs(float(widths[i + 1] - widths[i]))
        count = max(interval_count(qs[i], qs[i + 1], joint_step), int(np.ceil(linear / LINEAR_STEP)))
        fractions = np.arange(1, count + 1, dtype=float) / count
        parts_q.append(qs[i] + fractions[:, None] * (qs[i + 1] - qs[i]))
        parts_w.append(widths[i] + fractions * (widths[i + 1] - widths[i]))
        owners.append(np.full(count, i, dtype=int))
    return SegmentSamples(np.concatenate(parts_q), np.concatenate(parts_w), np.concatenate(owners))
