"""Execution under physics in a forked child, fed step by step as the kinematic judge reads the
plan: the same verdict and recording as in this process; the judge's steps survive pickling; a
child that fails says why; a cancelled child is gone."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from kitchen_tamp.execute import Verification, execute_under_physics, judged_pairs
from kitchen_tamp.execute.physics.background_physics import PendingPhysics, PhysicsError, PhysicsJob
from kitchen_tamp.execute.verification import judged_steps
from kitchen_tamp.kitchen import default_kitchen_map
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task

pytestmark = pytest.mark.slow  # each test executes a whole kitchen plan under physics


def test_the_judged_steps_survive_pickling(verified: Verification) -> None:
    for tracks, outcome in judged_steps(verified):
        tracks_back, outcome_back = pickle.loads(pickle.dumps((tracks, outcome)))
        assert outcome_back.arguments == outcome.arguments and outcome_back.held_box == outcome.held_box
        assert dict(outcome_back.openings) == dict(outcome.openings)
        assert dict(outcome_back.box_poses) == dict(outcome.box_poses)
        with pytest.raises(TypeError):  # read-only again
            outcome_back.openings["drawer"] = 0.0  # type: ignore[index]
        for track, back in zip(tracks, tracks_back, strict=True):
            assert back.carried == track.carried and back.gripped == track.gripped
            assert np.array_equal(back.samples.configurations, track.samples.configurations)
            assert {k: v.tolist() for k, v in back.openings.items()} == {
                k: v.tolist() for k, v in track.openings.items()}


def test_the_child_gives_the_verdict_and_recording_of_this_process(
    kitchen_task: Task, refined: KitchenTrajectory, verified: Verification
) -> None:
    job = PhysicsJob(kitchen_task, default_kitchen_map(), replan=None, record=True)
    pending = PendingPhysics(job)
    for step, judged in judged_pairs(refined, verified):
        pending.judged(step, judged)
    outcome = pending.result()
    here = execute_under_physics(kitchen_task, judged_pairs(refined, verified))
    assert outcome.execution.report_data() == here.report_data()
    assert outcome.recorded is not None and outcome.recorded.captured
    assert outcome.recorded.recording.times[-1] == pytest.approx(here.simulated_s, abs=0.05)


def test_a_failing_child_says_why(
    kitchen_task: Task, refined: KitchenTrajectory, verified: Verification
) -> None:
    job = PhysicsJob(kitchen_task, default_kitchen_map(), replan=None, record=False)
    pending = PendingPhysics(job)
    step, (tracks, outcome) = next(judged_pairs(refined, verified))
    pending.judged(step, (tracks[:1], outcome))  # the judge's reading of one segment of several
    with pytest.raises(PhysicsError, match="shorter"):
        pending.result()


def test_a_cancelled_child_is_gone(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    job = PhysicsJob(kitchen_task, default_kitchen_map(), replan=None, record=False)
    pending = PendingPhysics(job)
    process = pending._process
    pending.cancel()
    assert process is None or not process.is_alive()
