"""Replaying a refined plan through the problem's own dynamics checks it independently of the samplers."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from kitchen_tamp.bilevel import RefinedStep, Trajectory, plan_reaches_goal, replay_refined_plan, sesame
from kitchen_tamp.bilevel.toy_rooms import blocked_doorway


def test_replay_reproduces_the_sampled_states() -> None:
    problem = blocked_doorway().problem()
    plan = sesame(problem, seed=0).plan
    assert plan is not None
    replayed = replay_refined_plan(problem, plan)
    assert np.allclose(np.array(replayed.states), np.array(plan.trajectory.states))
    assert plan_reaches_goal(problem, plan)


def test_a_plan_whose_actions_stop_short_does_not_reach_the_goal() -> None:
    problem = blocked_doorway().problem()
    plan = sesame(problem, seed=0).plan
    assert plan is not None
    last = plan.steps[-1]
    stalled = Trajectory(last.trajectory.states, tuple(0.0 * u for u in last.trajectory.actions))
    tampered = replace(plan, steps=(*plan.steps[:-1], RefinedStep(last.index, last.transition, stalled)))
    assert not plan_reaches_goal(problem, tampered)


def test_replay_needs_a_transition_function() -> None:
    problem = blocked_doorway().problem()
    plan = sesame(problem, seed=0).plan
    assert plan is not None
    with pytest.raises(ValueError, match="no transition function"):
        replay_refined_plan(replace(problem, transition=None), plan)
