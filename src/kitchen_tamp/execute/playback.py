"""The states along a segment that verification checks.

A segment's waypoints may be far apart (a free-space move is a few joint-space
corners); ``interpolate_segment`` fills them in so no joint moves more than a
given step, and the gripper and drawer by no more than ``LINEAR_STEP``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.joint_spacing import interval_count
from kitchen_tamp.kitchen import Segment
from kitchen_tamp.world import FloatArray

LINEAR_STEP = 0.005
"""Largest change (m) of the gripper width or a drawer joint between interpolated states."""


@dataclass(frozen=True, eq=False)
class SegmentSamples:
    """States along a segment: arm configurations, gripper widths, drawer values (or None),
    and ``waypoint_of`` = the index of the waypoint each sample lies after."""

    configurations: FloatArray
    gripper_widths: FloatArray
    drawer_values: FloatArray | None
    waypoint_of: np.ndarray

    def __len__(self) -> int:
        return len(self.configurations)


def interpolate_segment(segment: Segment, joint_step: float) -> SegmentSamples:
    """Every waypoint, and between two waypoints evenly spaced states at most ``joint_step``
    apart by the rule of ``kitchen_tamp.joint_spacing``."""
    qs = segment.configurations
    widths = segment.gripper_widths
    drawer = segment.drawer_values
    parts_q: list[FloatArray] = [qs[:1]]
    parts_w: list[FloatArray] = [widths[:1]]
    parts_d: list[FloatArray] = [] if drawer is None else [drawer[:1]]
    owners: list[np.ndarray] = [np.zeros(1, dtype=int)]
    for i in range(len(qs) - 1):
        linear = abs(float(widths[i + 1] - widths[i]))
        if drawer is not None:
            linear = max(linear, abs(float(drawer[i + 1] - drawer[i])))
        count = max(interval_count(qs[i], qs[i + 1], joint_step), int(np.ceil(linear / LINEAR_STEP)))
        fractions = np.arange(1, count + 1, dtype=float) / count
        parts_q.append(qs[i] + fractions[:, None] * (qs[i + 1] - qs[i]))
        parts_w.append(widths[i] + fractions * (widths[i + 1] - widths[i]))
        if drawer is not None:
            parts_d.append(drawer[i] + fractions * (drawer[i + 1] - drawer[i]))
        owners.append(np.full(count, i, dtype=int))
    return SegmentSamples(
        np.concatenate(parts_q),
        np.concatenate(parts_w),
        None if drawer is None else np.concatenate(parts_d),
        np.concatenate(owners),
    )
