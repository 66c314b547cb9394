"""The time law physics execution follows: when the arm should be where along a segment.

A segment is cut into strokes at its sharp corners (the arm stops there); each
stroke is run with a trapezoidal speed profile whose top speed keeps every
joint within ``speed_fraction`` of its velocity limit and the fingers within
theirs, ramping up and down in ``ramp_s``.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.world import FloatArray

CORNER_COSINE = 0.95
"""Consecutive waypoint intervals whose joint-space directions have a lower cosine meet at a
corner where the arm stops."""


@dataclass(frozen=True)
class TimeLaw:
    """Speeds of the time law: a fraction of each joint's limit, and the ramp time."""

    speed_fraction: float = 0.5
    ramp_s: float = 0.25

    def __post_init__(self) -> None:
        if not 0.0 < self.speed_fraction <= 1.0 or self.ramp_s <= 0.0:
            raise ValueError(f"invalid time law: {self}")


DEFAULT_TIME_LAW = TimeLaw()


@dataclass(frozen=True, eq=False)
class Stroke:
    """Waypoints (configurations, widths) run in one go from rest to rest; ``lengths[i]`` is the
    time interval i takes at top speed; the stroke's first waypoint is waypoint ``first`` of
    its segment."""

    configurations: FloatArray
    widths: FloatArray
    lengths: FloatArray
    ramp_s: float
    first: int = 0

    @property
    def duration(self) -> float:
        """Seconds from rest to rest."""
        total = float(np.sum(self.lengths))
        if total >= self.ramp_s:
            return total + self.ramp_s
        return 2.0 * float(np.sqrt(total * self.ramp_s))

    def progress(self, times: FloatArray) -> tuple[FloatArray, FloatArray]:
        """(distance, speed) along the stroke, in top-speed seconds, at each of ``times``."""
        total = float(np.sum(self.lengths))
        duration = self.duration
        t = np.clip(np.asarray(times, dtype=float), 0.0, duration)
        acceleration = 1.0 / self.ramp_s
        peak = min(1.0, float(np.sqrt(acceleration * total)))
        ramp = peak / acceleration
        left = duration - t
        cruising = 0.5 * peak * ramp + peak * (t - ramp)
        stopping = total - 0.5 * acceleration * left * left
        distance = np.where(t < ramp, 0.5 * acceleration * t * t, np.where(left < ramp, stopping, cruising))
        speed = np.where(t < ramp, acceleration * t, np.where(left < ramp, acceleration * left, peak))
        return distance, speed

    def locate(self, times: FloatArray) -> tuple[np.ndarray, FloatArray, FloatArray]:
        """(waypoint interval of the stroke, fraction along it, speed in top-speed units) at
        each of ``times``."""
        distance, speed = self.progress(times)
        ends = np.cumsum(self.lengths)
        starts = ends - self.lengths
        i = np.clip(np.searchsorted(ends, distance, side="right"), 0, len(self.lengths) - 1)
        lengths = self.lengths[i]
        moving = lengths > 0.0
        safe = np.where(moving, lengths, 1.0)
        fraction = np.where(moving, np.clip((distance - starts[i]) / safe, 0.0, 1.0), 0.0)
        return i, fraction, np.where(moving, speed / safe, 0.0)

    def sample(self, times: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(configurations, joint velocities, gripper widths) at each of ``times``."""
        i, fraction, rate = self.locate(times)
        dq = self.configurations[i + 1] - self.configurations[i]
        q = self.configurations[i] + fraction[:, None] * dq
        widths = self.widths[i] + fraction * (self.widths[i + 1] - self.widths[i])
        return q, dq * rate[:, None], widths


def strokes(
    configurations: FloatArray,
    widths: FloatArray,
    joint_speeds: FloatArray,
    finger_speed: float,
    law: TimeLaw,
) -> list[Stroke]:
    """A segment's waypoints as strokes; ``joint_speeds`` are the joints' velocity limits and
    ``finger_speed`` the gripper width's (m/s)."""
    dq = np.diff(configurations, axis=0)
    joint_time = np.max(np.abs(dq) / (law.speed_fraction * joint_speeds), axis=1)
    width_time = np.abs(np.diff(widths)) / (law.speed_fraction * finger_speed)
    lengths = np.maximum(joint_time, width_time)
    norms = np.linalg.norm(dq, axis=1)
    cuts = [0]
    for i in range(1, len(dq)):
        if norms[i] > 0.0 and norms[i - 1] > 0.0:
            cosine = float(np.dot(dq[i], dq[i - 1]) / (norms[i] * norms[i - 1]))
            if cosine < CORNER_COSINE:
                cuts.append(i)
    cuts.append(len(dq))
    return [
        Stroke(configurations[a : b + 1], widths[a : b + 1], lengths[a:b], law.ramp_s, a)
        for a, b in itertools.pairwise(cuts)
        if b > a
    ]
