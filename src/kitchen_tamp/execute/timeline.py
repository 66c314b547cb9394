"""Time along a trajectory: each waypoint interval takes as long as its slowest joint
(or the gripper, or the drawer) needs at nominal speeds, so pictures and plots of a run
share one clock."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen import KitchenScene, Segment, enter_segment, set_waypoint
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.world import FloatArray

JOINT_SPEED = 1.0
"""Nominal joint speed (rad/s)."""
LINEAR_SPEED = 0.1
"""Nominal gripper and drawer speed (m/s)."""
MIN_INTERVAL = 0.02
"""Shortest time (s) between two waypoints, so that pauses (gripper changes) are visible."""


@dataclass(frozen=True, eq=False)
class TimedSegment:
    """A segment of step ``step`` with the absolute time of each waypoint."""

    step: int
    segment: Segment
    times: FloatArray

    @property
    def start(self) -> float:
        return float(self.times[0])

    @property
    def end(self) -> float:
        return float(self.times[-1])


def waypoint_intervals(segment: Segment) -> FloatArray:
    """Seconds between consecutive waypoints of ``segment``."""
    joint = np.max(np.abs(np.diff(segment.configurations, axis=0)), axis=1) / JOINT_SPEED
    linear = np.abs(np.diff(segment.gripper_widths)) / LINEAR_SPEED
    if segment.drawer_values is not None:
        linear = np.maximum(linear, np.abs(np.diff(segment.drawer_values)) / LINEAR_SPEED)
    return np.asarray(np.maximum(np.maximum(joint, linear), MIN_INTERVAL))


@dataclass(frozen=True, eq=False)
class Timeline:
    """Every segment of a trajectory on one clock starting at 0."""

    segments: tuple[TimedSegment, ...]
    step_starts: FloatArray
    actions: tuple[str, ...]

    @property
    def duration(self) -> float:
        return self.segments[-1].end if self.segments else 0.0

    def joint_samples(self) -> tuple[FloatArray, FloatArray]:
        """(times, configurations) of every waypoint, in order."""
        if not self.segments:
            return np.zeros(0), np.zeros((0, 0))
        times = np.concatenate([s.times for s in self.segments])
        qs = np.concatenate([s.segment.configurations for s in self.segments])
        return times, qs

    def play(self, kitchen: KitchenScene, frame_times: FloatArray) -> Iterator[tuple[float, int]]:
        """Pose ``kitchen`` at each of the increasing ``frame_times`` in turn (attaching and
        releasing boxes as segments begin) and yield (time, step index) at each."""
        times = np.asarray(frame_times, dtype=float)
        cursor = 0
        for timed in self.segments:
            segment = timed.segment
            enter_segment(kitchen, segment)
            last = timed is self.segments[-1]
            while cursor < len(times) and (
                times[cursor] < timed.end or (last and times[cursor] <= timed.end)
            ):
                t = float(times[cursor])
                i = int(np.clip(np.searchsorted(timed.times, t, side="right") - 1, 0, len(timed.times) - 2))
                span = timed.times[i + 1] - timed.times[i]
                set_waypoint(kitchen, segment, i, float(np.clip((t - timed.times[i]) / span, 0.0, 1.0)))
                yield t, timed.step
                cursor += 1


def build_timeline(trajectory: KitchenTrajectory) -> Timeline:
    """Put every waypoint of ``trajectory`` on one clock."""
    timed: list[TimedSegment] = []
    starts: list[float] = []
    clock = 0.0
    for index, step in enumerate(trajectory.steps):
        starts.append(clock)
        for segment in step.segments:
            times = clock + np.concatenate([[0.0], np.cumsum(waypoint_intervals(segment))])
            timed.append(TimedSegment(index, segment, times))
            clock = float(times[-1])
    return Timeline(tuple(timed), np.asarray(starts), tuple(trajectory.plan))
