"""What a failed skill teaches the abstract search: a confirmed obstruction as the absence of the
blocker's location atoms, a place out of reach as every placement onto it pruned; and SeSamE in
the kitchen moving the blocker first because of it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.bilevel import Obstruction, Outcome, SesameBudgets, Unreachable
from kitchen_tamp.kitchen import (
    KitchenScene,
    SkillFailure,
    build_kitchen_for_task,
    load_kitchen_map,
    sample_targets,
)
from kitchen_tamp.kitchen.skills.obstructions import confirm_unreachable
from kitchen_tamp.planning import Task, load_task
from kitchen_tamp.refinement import SamplingMotionBackend
from kitchen_tamp.refinement.failure_feedback import FailureFeedback
from kitchen_tamp.refinement.kitchen_sesame import RefinementOptions, refine_with_sesame
from kitchen_tamp.shipped_kitchens import kitchen_folder

BENCHMARKS = kitchen_folder("benchmarks")
DOMAIN = BENCHMARKS / "domain.pddl"
FAR_PLATE = Path(__file__).resolve().parents[1] / "kitchen" / "problems" / "far_plate"


def task_and_kitchen(folder: Path) -> tuple[Task, KitchenScene]:
    task = load_task(folder / "problem.pddl", DOMAIN)
    return task, build_kitchen_for_task(task, kitchen_map=load_kitchen_map(folder / "scene.toml", DOMAIN))


def failure_of(kitchen: KitchenScene, task: Task, text: str) -> tuple[object, SkillFailure]:
    name, *args = text.split()
    action = task.action_named(name, args)
    assert action is not None
    with pytest.raises(SkillFailure) as failed:
        sample_targets(kitchen, name, tuple(args), np.random.default_rng(0))
    return action, failed.value


@pytest.mark.slow
def test_a_confirmed_obstruction_teaches_the_blockers_location_and_is_kept() -> None:
    task, kitchen = task_and_kitchen(BENCHMARKS / "blocked")
    with kitchen:
        action, failure = failure_of(kitchen, task, "pick green table")
        feedback = FailureFeedback(kitchen, task, np.random.default_rng(0))
        facts = feedback.facts(action, task.initial_state, failure)  # type: ignore[arg-type]
        assert facts == (Obstruction(("pick", ("green", "table")), frozenset({("on", "blocker", "table")}),
                                     ("blocker",)),)
        assert feedback.facts(action, task.initial_state, failure) == facts  # type: ignore[arg-type]
        assert feedback.confirmations == 1  # the second time from the same state costs no check


@pytest.mark.slow
def test_a_place_out_of_reach_prunes_every_placement_onto_it() -> None:
    task, kitchen = task_and_kitchen(FAR_PLATE)
    with kitchen:
        sample_targets(kitchen, "pick", ("green", "table"), np.random.default_rng(0)).apply(kitchen)
        holding = task.state_from_atoms({("holding", "green")})
        action, failure = failure_of(kitchen, task, "place green far_plate")
        feedback = FailureFeedback(kitchen, task, np.random.default_rng(0))
        facts = feedback.facts(action, holding, failure)  # type: ignore[arg-type]
        assert facts == (Unreachable("far_plate", frozenset({("place", ("green", "far_plate"))})),)
        near = task.action_named("place", ["green", "plate"])
        assert near is not None and not confirm_unreachable(kitchen, near, np.random.default_rng(0), "plate")
        assert kitchen.held_box() == "green"  # the checks leave the scene as it was


@pytest.mark.slow
@pytest.mark.parametrize("feedback", [True, False])
def test_sesame_moves_the_blocker_first_once_it_is_learned(feedback: bool) -> None:
    task, kitchen = task_and_kitchen(BENCHMARKS / "blocked")
    budgets = SesameBudgets(max_plans=2, samples_per_step=2, max_samples=30, time_budget_s=900.0)
    with kitchen:
        outcome = refine_with_sesame(kitchen, task, SamplingMotionBackend(), 0, budgets,
                                     RefinementOptions(feedback=feedback))
    first = outcome.result.attempts[0]
    assert [a.text for a in first.abstract_plan.actions] == ["(pick green table)", "(place green plate)"]
    if feedback:
        assert first.outcome is Outcome.PLAN_REFUTED and outcome.refined is not None
        assert outcome.report_data()["learned"] == [
            "(pick green table) is obstructed by blocker while (on blocker table)"]
        assert outcome.refined.trajectory.plan.index("(pick blocker table)") == 0
    else:
        assert first.outcome is Outcome.STEPS_EXHAUSTED and "learned" not in outcome.report_data()
