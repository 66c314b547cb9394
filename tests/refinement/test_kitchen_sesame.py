"""The kitchen through SeSamE: refined plans verify, and when an action cannot be refined
from where the previous one left the scene, SeSamE steps back and resamples it."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.execute import verify_trajectory
from kitchen_tamp.kitchen import KitchenScene, build_kitchen_for_task
from kitchen_tamp.planning import GroundAction, load_task
from kitchen_tamp.refinement import SamplingMotionBackend, kitchen_sesame
from kitchen_tamp.refinement.kitchen_sesame import KITCHEN_BUDGETS, refine_with_sesame
from kitchen_tamp.refinement.motion_backend import MotionBackend
from kitchen_tamp.refinement.refine_action import ActionSampleRecord

pytestmark = pytest.mark.slow  # each test runs or replays a whole kitchen pipeline

PROBLEM = Path(__file__).resolve().parents[2] / "pddl" / "problem.pddl"


def test_sesame_refines_the_kitchen_problem_and_the_result_verifies() -> None:
    task = load_task(PROBLEM)
    with build_kitchen_for_task(task) as kitchen:
        outcome = refine_with_sesame(kitchen, task, SamplingMotionBackend(), seed=0)
    assert outcome.refined is not None
    assert outcome.result.counts.abstract_plans == 1 and outcome.result.counts.backtracks == 0
    assert [r.index for r in outcome.refined.records] == list(range(5))
    with build_kitchen_for_task(task) as fresh:
        assert verify_trajectory(fresh, task, outcome.refined.trajectory).verified


@pytest.fixture
def place_refused_until_second_pick(monkeypatch: pytest.MonkeyPatch) -> None:
    """Placing the spam fails unless its pick was sampled at least twice: only stepping back helps."""
    real = kitchen_sesame.refine_action
    picks = {"count": 0}

    def picky(
        kitchen: KitchenScene,
        index: int,
        action: GroundAction,
        backend: MotionBackend,
        rng: np.random.Generator,
        **options: object,
    ) -> tuple[object, ActionSampleRecord]:
        if action.name == "pickUp" and action.args[0] == "spam":
            picks["count"] += 1
        if action.name == "placeIn" and picks["count"] < 2:
            return None, ActionSampleRecord(
                index=index,
                action=action.text,
                planner="test",
                solved=False,
                skill_samples=0,
                motion_attempts=0,
                motion={},
                waypoints=0,
                rejections=("refused by the test",),
            )
        return real(kitchen, index, action, backend, rng, **options)  # type: ignore[arg-type]

    monkeypatch.setattr(kitchen_sesame, "refine_action", picky)


@pytest.mark.usefixtures("place_refused_until_second_pick")
def test_sesame_backtracks_when_an_action_fails_from_the_previous_outcome() -> None:
    task = load_task(PROBLEM)
    with build_kitchen_for_task(task) as kitchen:
        outcome = refine_with_sesame(
            kitchen, task, SamplingMotionBackend(), seed=0,
            budgets=replace(KITCHEN_BUDGETS, max_plans=1, samples_per_step=2, max_samples=40),
        )
    assert outcome.refined is not None, outcome.result.detail
    assert outcome.result.counts.backtracks >= 1
    assert outcome.result.counts.failures >= 2
    with build_kitchen_for_task(task) as fresh:
        assert verify_trajectory(fresh, task, outcome.refined.trajectory).verified


@pytest.mark.usefixtures("place_refused_until_second_pick")
def test_greedy_budgets_fail_where_backtracking_succeeds() -> None:
    task = load_task(PROBLEM)
    with build_kitchen_for_task(task) as kitchen:
        greedy = refine_with_sesame(
            kitchen, task, SamplingMotionBackend(), seed=0,
            budgets=replace(KITCHEN_BUDGETS, max_plans=1, samples_per_step=1, max_samples=40),
        )
    assert greedy.refined is None
    assert greedy.result.counts.backtracks == 0
