"""A kitchen problem where greedy refinement fails for a geometric reason and SeSamE,
stepping back to the pick, succeeds: pddl/problem_baguette.pddl.

The baguette box (6 x 6 x 50 cm) is longer than the drawer's diagonal, so it fits in
the drawer only standing up, and then only if the hand holds it above the drawer's
walls. With seed 7 the first pick holds it so that no placement works; greedy
refinement never revisits the pick and fails, SeSamE re-grasps.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from kitchen_tamp.bilevel import SesameBudgets
from kitchen_tamp.execute import verify_trajectory
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.planning import Task, load_task
from kitchen_tamp.refinement import (
    KITCHEN_BUDGETS,
    SamplingMotionBackend,
    SesameRefinement,
    refine_with_sesame,
)

pytestmark = pytest.mark.slow  # each test runs or replays a whole kitchen pipeline

PROBLEM = Path(__file__).resolve().parents[2] / "pddl" / "problem_baguette.pddl"
SEED = 7


@pytest.fixture(scope="module")
def task() -> Task:
    return load_task(PROBLEM)


def _refine(task: Task, budgets: SesameBudgets) -> SesameRefinement:
    with build_kitchen_for_task(task) as kitchen:
        return refine_with_sesame(kitchen, task, SamplingMotionBackend(), seed=SEED, budgets=budgets)


def test_greedy_refinement_fails_at_the_placement(task: Task) -> None:
    greedy = _refine(task, replace(KITCHEN_BUDGETS, max_plans=1, samples_per_step=1, max_samples=10))
    assert greedy.refined is None
    (attempt,) = greedy.result.attempts
    stuck = [step for step in attempt.steps if step.failures]
    assert [step.action.text for step in stuck] == ["(placeIn baguette drawer)"]
    assert "placement" in (stuck[0].last_failure or "")
    assert greedy.result.counts.backtracks == 0


def test_sesame_regrasps_and_the_result_verifies(task: Task) -> None:
    outcome = _refine(task, KITCHEN_BUDGETS)
    assert outcome.refined is not None, outcome.result.detail
    assert outcome.result.counts.backtracks >= 1  # it went back to the pick
    assert outcome.result.counts.abstract_plans == 1
    with build_kitchen_for_task(task) as fresh:
        verification = verify_trajectory(fresh, task, outcome.refined.trajectory)
        assert verification.verified, verification.problems
        box_centre = fresh.box("baguette").base_pose().translation
        place = outcome.refined.trajectory.steps[-1]
        descend = next(s for s in place.segments if s.name == "descend")
        hand = fresh.robot.forward_kinematics(descend.configurations[-1]).translation
    assert hand[2] > box_centre[2]  # standing in the drawer, held by its upper half
