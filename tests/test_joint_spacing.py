"""One spacing rule for every segment check: the planners' checkers and the judge agree."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.joint_spacing import coarse_to_fine_order, interior_fractions, interval_count
from kitchen_tamp.kitchen import Segment
from kitchen_tamp.kitchen.segment import interpolate_segment
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker


class _CountingWorld:
    """Every configuration free; remembers what it was asked."""

    def __init__(self) -> None:
        self.asked: list[np.ndarray] = []

    def is_valid(self, qs: np.ndarray) -> np.ndarray:
        self.asked.append(np.array(qs))
        return np.ones(len(qs), dtype=bool)

    def segment_valid(self, q0: np.ndarray, q1: np.ndarray) -> bool:
        return True


def test_spacing_is_euclidean_over_the_joints() -> None:
    # every joint moves 0.01 rad: the largest joint step is 0.01 but the move is 0.02 long
    q0, q1 = np.zeros(4), np.full(4, 0.01)
    assert interval_count(q0, q1, 0.005) == 4
    assert interval_count(q0, q0, 0.005) == 1
    with pytest.raises(ValueError):
        interval_count(q0, q1, 0.0)


def test_interior_fractions_visit_every_state_once_coarse_to_fine() -> None:
    fractions = interior_fractions(np.zeros(2), np.array([0.08, 0.0]), 0.01)
    assert fractions[0] == pytest.approx(0.5)
    assert sorted(fractions) == pytest.approx([k / 8 for k in range(1, 8)])
    assert sorted(coarse_to_fine_order(7)) == list(range(7))


def test_planner_checker_and_judge_check_the_same_states() -> None:
    q0, q1 = np.zeros(7), np.linspace(0.05, 0.35, 7)
    world = _CountingWorld()
    segments = CountingSegmentChecker(world, resolution=0.005)
    assert segments.segment_valid(q0, q1)
    planner_states = np.concatenate(world.asked)
    segment = Segment("move", np.stack([q0, q1]), np.zeros(2))
    judge_states = interpolate_segment(segment, 0.005).configurations

    def as_set(states: np.ndarray) -> set[tuple[float, ...]]:
        return {tuple(np.round(q, 9)) for q in states}

    assert as_set(planner_states) == as_set(judge_states)
    assert len(planner_states) == len(judge_states) == interval_count(q0, q1, 0.005) + 1
