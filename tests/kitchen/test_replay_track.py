"""A replayed segment's states are found from a point along a waypoint interval (how physics
reads the judge's state at each tick), and a waypoint the robot cannot take is named with
its joint and the limit it passes."""

from __future__ import annotations

from collections.abc import Iterator
from types import MappingProxyType

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene, Segment, build_kitchen_for_task
from kitchen_tamp.kitchen.replay_track import SegmentTrack
from kitchen_tamp.kitchen.robot_range import clipped_to_range, range_problem
from kitchen_tamp.kitchen.segment import interpolate_segment
from tests.kitchen.conftest import REPO, task_of


def _track(segment: Segment, step: float) -> SegmentTrack:
    samples = interpolate_segment(segment, step)
    count = len(samples)
    return SegmentTrack(segment, samples, (None,) * count, (None,) * count, MappingProxyType({}))


def test_the_state_at_a_point_of_an_interval_lies_on_it() -> None:
    qs = np.array([[0.0, 0.0], [0.1, 0.0], [0.1, 0.3], [0.1, 0.31]])
    segment = Segment("s", qs, np.full(4, 0.08))
    track = _track(segment, 0.01)
    intervals, fractions = np.repeat(np.arange(3), 11), np.tile(np.linspace(0.0, 1.0, 11), 3)
    states = track.states_at(intervals, fractions)
    for interval, fraction, state in zip(intervals, fractions, states, strict=True):
        wanted = qs[interval] + fraction * (qs[interval + 1] - qs[interval])
        assert np.linalg.norm(track.samples.configurations[state] - wanted) <= 0.005 + 1e-12
    assert states[0] == 0 and states[-1] == len(track) - 1


@pytest.fixture(scope="module")
def kitchen() -> Iterator[KitchenScene]:
    with build_kitchen_for_task(task_of(REPO / "pddl" / "problem.pddl")) as built:
        yield built


def test_a_waypoint_out_of_range_is_named_with_its_joint_and_limit(kitchen: KitchenScene) -> None:
    robot = kitchen.robot
    home = kitchen.home
    inside = Segment("move", np.stack([home, home]), np.full(2, 0.08))
    assert range_problem(robot, inside) is None
    past = home.copy()
    past[5] = robot.lower[5] - 0.01
    segment = Segment("move", np.stack([home, past, home]), np.full(3, 0.08))
    assert range_problem(robot, segment) == (
        f"waypoint 1: panda_joint6 at {past[5]:.4f} rad is past its lower limit -0.0175 rad "
        "(the stricter of the URDF's <limit> and <safety_controller>)"
    )
    wide = Segment("move", np.stack([home, home]), np.array([0.08, 0.081]))
    wide_problem = "waypoint 1: gripper width 0.0810 m is outside the hand's range [0, 0.080] m"
    assert range_problem(robot, wide) == wide_problem
    clipped = clipped_to_range(robot, segment)
    assert range_problem(robot, clipped) is None and clipped.configurations[1, 5] == robot.lower[5]
