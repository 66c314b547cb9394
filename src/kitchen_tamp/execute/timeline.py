"""Time along a trajectory: each waypoint interval takes as long as its slowest joint
(or the gripper) needs at nominal speeds, so pictures and plots of a run share one clock.

Playing a timeline poses the kitchen at the states the judge replayed
(``Verification.tracks``), so what the pictures show riding with the hand and
where they show the drawer are what the judge derived, not what a file says.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen import KitchenScene, Segment, SegmentTrack
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.world import FloatArray

JOINT_SPEED = 1.0
"""Nominal joint speed (rad/s)."""
LINEAR_SPEED = 0.1
"""Nominal gripper speed (m/s)."""
MIN_INTERVAL = 0.02
"""Shortest time (s) between two waypoints, so that pauses (gripper changes) are visible."""


@dataclass(frozen=True, eq=False)
class TimedSegment:
    """A segment of step ``step`` with the absolute time of each waypoint, and as the judge
    replayed it (``track``: its states, with the time of each in ``state_times``)."""

    step: int
    segment: Segment
    times: FloatArray
    track: SegmentTrack
    state_times: FloatArray

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
        """Pose ``kitchen`` (built fresh for the problem) at each of the increasing
        ``frame_times`` in turn, at the last replayed state not after it, and yield
        (time, step index) at each. Every state where a box is taken or let go is
        visited, so boxes end up where the judge left them."""
        times = np.asarray(frame_times, dtype=float)
        cursor = 0
        for timed in self.segments:
            track, last_segment = timed.track, timed is self.segments[-1]
            for index in range(len(track)):
                due = (
                    float(timed.state_times[index + 1])
                    if index + 1 < len(track)
                    else (np.inf if last_segment else timed.end)
                )
                changes = index > 0 and track.carried[index] is not track.carried[index - 1]
                wanted = cursor < len(times) and times[cursor] < due
                if index == 0 or changes or wanted:
                    track.pose(kitchen, index)
                while cursor < len(times) and times[cursor] < due:
                    yield float(times[cursor]), timed.step
                    cursor += 1


def state_times(segment: Segment, track: SegmentTrack, times: FloatArray) -> FloatArray:
    """The time of each replayed state: its waypoint interval's share, evenly spaced."""
    owners = np.asarray(track.samples.waypoint_of[1:])
    counts = np.bincount(owners, minlength=len(segment) - 1)
    first_of = np.concatenate([[0], np.cumsum(counts)[:-1]])
    position = np.arange(len(owners)) - first_of[owners] + 1
    fractions = position / counts[owners]
    inner = times[owners] + fractions * (times[owners + 1] - times[owners])
    return np.concatenate([[times[0]], inner])


def build_timeline(trajectory: KitchenTrajectory, tracks: Sequence[Sequence[SegmentTrack]]) -> Timeline:
    """Put every waypoint of ``trajectory`` on one clock, with the judge's replay of each
    segment (``tracks``, step by step, as ``Verification.tracks``)."""
    timed: list[TimedSegment] = []
    starts: list[float] = []
    clock = 0.0
    for index, (step, step_tracks) in enumerate(zip(trajectory.steps, tracks, strict=True)):
        starts.append(clock)
        for segment, track in zip(step.segments, step_tracks, strict=True):
            times = clock + np.concatenate([[0.0], np.cumsum(waypoint_intervals(segment))])
            timed.append(TimedSegment(index, segment, times, track, state_times(segment, track, times)))
            clock = float(times[-1])
    return Timeline(tuple(timed), np.asarray(starts), tuple(trajectory.plan))
