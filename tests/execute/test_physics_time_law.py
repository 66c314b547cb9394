"""The physics time law keeps joints within their speed limit, stops at sharp corners and
ends exactly at the last waypoint; grip events are found from gripper widths alone."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.execute.physics.plan import grip_events
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


def test_grip_events_are_where_fingers_finish_closing_and_start_opening() -> None:
    events = grip_events([np.full(4, 0.08), np.array([0.08, 0.06, 0.05]), np.full(3, 0.05),
                          np.array([0.05, 0.05, 0.08])])
    assert [(e.segment, e.waypoint, e.closing) for e in events] == [(1, 2, True), (3, 1, False)]
