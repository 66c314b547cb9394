"""SeSamE in the regions domain: a skill's failure reaches the planning graph with its kind and the
objects that obstructed it (what the abstract level is to learn from), and the conditions an
action's effects set (clean, cooked) are part of the low-level state SeSamE carries."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from kitchen_tamp.kitchen import FailureKind, abstract_state, build_kitchen_for_task, load_kitchen_map
from kitchen_tamp.planning import Task, load_task
from kitchen_tamp.refinement import SamplingMotionBackend
from kitchen_tamp.refinement.kitchen_sesame import KITCHEN_BUDGETS, SkillSamplingFailure, refine_with_sesame
from kitchen_tamp.shipped_kitchens import kitchen_folder

pytestmark = pytest.mark.slow  # each test runs SeSamE on a kitchen

BENCHMARKS = kitchen_folder("benchmarks")


def _load(family: str, problem: str) -> tuple[Task, Path]:
    folder = BENCHMARKS / family
    return load_task(folder / problem, folder / "domain.pddl"), folder


def test_an_obstructed_pick_reaches_the_planning_graph_naming_the_blocker() -> None:
    task, folder = _load("blocked", "problem.pddl")
    kitchen_map = load_kitchen_map(folder / "scene.toml", folder / "domain.pddl")
    budgets = replace(KITCHEN_BUDGETS, max_plans=1, samples_per_step=1, max_samples=4)
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        outcome = refine_with_sesame(kitchen, task, SamplingMotionBackend(), seed=0, budgets=budgets)
    assert outcome.refined is None  # the shortest plan picks the green block where it stands
    (failed,) = outcome.result.graph.failed_samples
    assert failed.transition.action.text == "(pick green table)"
    assert isinstance(failed.error, SkillSamplingFailure)
    skill_failure = failed.error.skill_failure
    assert skill_failure is not None
    assert skill_failure.kind is FailureKind.OBSTRUCTED and skill_failure.objects[0] == "blocker"
    assert skill_failure.region == "table"


def test_washing_and_cooking_set_conditions_the_refined_state_keeps() -> None:
    task, folder = _load("kitchen", "problem_radish.pddl")
    kitchen_map = load_kitchen_map(folder / "scene.toml", folder / "domain.pddl")
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        outcome = refine_with_sesame(kitchen, task, SamplingMotionBackend(), seed=0)
        assert outcome.refined is not None, outcome.result.detail
        assert [s.action for s in outcome.refined.trajectory.steps][2] == "(wash radish sink)"
        final = abstract_state(kitchen, task.objects)
    assert {("cooked", "radish"), ("clean", "radish"), ("on", "radish", "tray")} <= final
