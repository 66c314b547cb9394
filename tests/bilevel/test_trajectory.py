from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.bilevel import AbstractPlan, Trajectory, concatenate, rollout


def test_rollout_applies_the_transition_and_keeps_every_state() -> None:
    trajectory = rollout(lambda x, u: x + u, 1, [2, 3])
    assert trajectory.states == (1, 3, 6)
    assert trajectory.actions == (2, 3)
    assert (trajectory.initial_state, trajectory.final_state, len(trajectory)) == (1, 6, 2)


def test_a_trajectory_needs_one_state_more_than_actions() -> None:
    with pytest.raises(ValueError, match="needs 3 states"):
        Trajectory((1, 2), ("a", "b"))
    with pytest.raises(ValueError, match="start state"):
        Trajectory((), ())


def test_states_need_not_be_hashable() -> None:
    trajectory = rollout(lambda x, u: x + u, np.zeros(2), [np.ones(2)])
    assert np.array_equal(trajectory.final_state, np.ones(2))


def test_concatenation_drops_the_repeated_joints() -> None:
    first = rollout(lambda x, u: x + u, 0, [1, 1])
    second = rollout(lambda x, u: x + u, 2, [5])
    joined = concatenate([first, second], 0)
    assert joined.states == (0, 1, 2, 7)
    assert joined.actions == (1, 1, 5)
    assert concatenate([], 4).states == (4,)


def test_abstract_plan_transitions_chain_its_states() -> None:
    plan = AbstractPlan(("A", "B", "C"), ("ab", "bc"))
    assert [(t.source, t.action, t.target) for t in plan.transitions] == [("A", "ab", "B"), ("B", "bc", "C")]
    with pytest.raises(ValueError):
        AbstractPlan(("A",), ("ab",))
