"""The physics time law keeps joints within their speed limit, stops at sharp corners, ends
exactly at the last waypoint, and says where along the segment each moment is (so physics
reads the judge's state there)."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.execute.physics.time_law import TimeLaw, strokes

LIMITS = np.array([2.0, 2.0, 1.0])


def _run(qs: np.ndarray, widths: np.ndarray, law: TimeLaw) -> list[tuple[np.ndarray, np.ndarray]]:
    samples = []
    for stroke in strokes(qs, widths, LIMITS, 0.2, law):
        times = np.linspace(0.0, stroke.duration, 400)
        q, qd, _ = stroke.sample(times)
        samples.append((q, qd))
    return samples


def test_speeds_stay_within_the_fraction_of_each_joint_limit() -> None:
    qs = np.array([[0.0, 0.0, 0.0], [1.0, 0.5, 0.2], [2.0, 1.0, 0.4]])
    law = TimeLaw(speed_fraction=0.5, ramp_s=0.2)
    for q, qd in _run(qs, np.zeros(3), law):
        assert np.all(np.abs(qd) <= law.speed_fraction * LIMITS + 1e-9)
        numeric = np.diff(q, axis=0) / np.diff(np.linspace(0.0, 1.0, len(q)))[:, None]
        assert np.all(np.isfinite(numeric))
    (q, qd), = _run(qs, np.zeros(3), law)
    assert np.allclose(q[0], qs[0]) and np.allclose(q[-1], qs[-1])
    assert np.allclose(qd[0], 0.0) and np.allclose(qd[-1], 0.0)


def test_a_sharp_corner_splits_the_motion_into_strokes_that_stop_there() -> None:
    qs = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
    parts = _run(qs, np.zeros(3), TimeLaw())
    assert len(parts) == 2
    assert np.allclose(parts[0][0][-1], qs[1]) and np.allclose(parts[0][1][-1], 0.0)


def test_a_gripper_only_segment_takes_the_time_the_fingers_need() -> None:
    qs = np.zeros((2, 3))
    (stroke,) = strokes(qs, np.array([0.08, 0.04]), LIMITS, 0.2, TimeLaw(speed_fraction=0.5, ramp_s=0.1))
    assert stroke.duration >= 0.04 / (0.5 * 0.2)
    _, _, widths = stroke.sample(np.array([0.0, stroke.duration]))
    assert np.allclose(widths, [0.08, 0.04])


def test_every_moment_is_located_on_its_waypoint_interval() -> None:
    qs = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 0.0]])
    first, second = strokes(qs, np.zeros(4), LIMITS, 0.2, TimeLaw())
    assert (first.first, second.first) == (0, 1)
    times = np.linspace(0.0, second.duration, 50)
    intervals, fractions, _ = second.locate(times)
    q, _, _ = second.sample(times)
    assert np.all(np.diff(second.first + intervals) >= 0) and set(second.first + intervals) == {1, 2}
    located = qs[second.first + intervals] + fractions[:, None] * (
        qs[second.first + intervals + 1] - qs[second.first + intervals]
    )
    assert np.allclose(located, q)
