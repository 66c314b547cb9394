"""The benchmark families shipped in ``shipped_kitchens/benchmarks``: every scene and problem lays
out with Ψ equal to its ``:init``, the shortest abstract plans are what they are documented to be,
and each family's hard part is real (the shortest plan fails geometrically where it should, with
the obstructing objects named)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import (
    FailureKind,
    KitchenScene,
    SkillFailure,
    abstract_state,
    build_kitchen_for_task,
    load_kitchen_map,
    sample_targets,
)
from kitchen_tamp.planning import Task, load_task, plan
from kitchen_tamp.shipped_kitchens import kitchen_folder

BENCHMARKS = kitchen_folder("benchmarks")
FAMILIES = ("nonmonotonic", "blocked", "packed", "kitchen", "towers", "sort_clutter")
PROBLEMS = sorted(p for family in FAMILIES for p in (BENCHMARKS / family).glob("problem*.pddl"))
SHORTEST = {
    "nonmonotonic/problem.pddl": 4,
    "blocked/problem.pddl": 2,
    "packed/problem.pddl": 10,
    "kitchen/problem.pddl": 11,
    "kitchen/problem_radish.pddl": 8,
    "towers/problem_sussman.pddl": 6,
    "towers/problem_reversal.pddl": 6,
    "sort_clutter/problem.pddl": 10,
}


def name_of(problem: Path) -> str:
    return f"{problem.parent.name}/{problem.name}"


def task_and_kitchen(problem: Path) -> tuple[Task, KitchenScene]:
    task = load_task(problem, problem.parent / "domain.pddl")
    kitchen_map = load_kitchen_map(problem.parent / "scene.toml", problem.parent / "domain.pddl")
    return task, build_kitchen_for_task(task, kitchen_map=kitchen_map)


def test_every_family_ships_a_scene_and_problems_with_the_regions_domain_beside_them() -> None:
    assert sorted(p.name for p in BENCHMARKS.iterdir() if p.is_dir()) == sorted(FAMILIES)
    for family in FAMILIES:
        folder = BENCHMARKS / family
        assert (folder / "scene.toml").is_file() and list(folder.glob("problem*.pddl"))
        assert (folder / "domain.pddl").read_text() == (BENCHMARKS / "domain.pddl").read_text()
        scene = (folder / "scene.toml").read_text()
        assert scene.startswith("# "), "each scene says what it is and where it comes from"
    assert {name_of(p) for p in PROBLEMS} == set(SHORTEST)


@pytest.mark.parametrize("problem", PROBLEMS, ids=name_of)
def test_each_problem_lays_out_as_its_init_says(problem: Path) -> None:
    task, kitchen = task_and_kitchen(problem)
    with kitchen:
        assert abstract_state(kitchen, task.objects) == task.init_atoms


@pytest.mark.parametrize("problem", PROBLEMS, ids=name_of)
def test_the_shortest_abstract_plan_has_the_documented_length(problem: Path) -> None:
    task = load_task(problem, problem.parent / "domain.pddl")
    if problem.parent.name == "sort_clutter":
        # too many boxes for breadth-first search; every goal atom needs its own pick and place,
        # so a plan of twice as many actions as goal atoms is a shortest one
        result = plan(task, "gbfs")
        assert result.plan is not None and len(result.plan) == 2 * len(task.goal_atoms)
    else:
        result = plan(task, "bfs")
    assert result.plan is not None and len(result.plan) == SHORTEST[name_of(problem)]


def test_towers_sussman_undoes_the_first_goal_on_the_way() -> None:
    task = load_task(BENCHMARKS / "towers" / "problem_sussman.pddl", BENCHMARKS / "towers" / "domain.pddl")
    result = plan(task, "bfs")
    assert result.plan is not None
    assert [a.text for a in result.plan][:2] == ["(unstack c a)", "(place c table)"]


def test_kitchen_cooks_only_what_was_washed() -> None:
    task = load_task(BENCHMARKS / "kitchen" / "problem_radish.pddl", BENCHMARKS / "kitchen" / "domain.pddl")
    result = plan(task, "bfs")
    assert result.plan is not None
    names = [a.name for a in result.plan]
    assert names.index("wash") < names.index("cook")


def _first_failing_pick(problem: Path, box: str) -> SkillFailure:
    _, kitchen = task_and_kitchen(problem)
    with kitchen, pytest.raises(SkillFailure) as failed:
        sample_targets(kitchen, "pick", (box, "table"), np.random.default_rng(0))
    return failed.value


@pytest.mark.parametrize(("box", "blocker"), [("red_box", "red_blocker"), ("blue_box", "blue_blocker")])
def test_nonmonotonic_each_box_is_obstructed_by_its_blocker(box: str, blocker: str) -> None:
    failure = _first_failing_pick(BENCHMARKS / "nonmonotonic" / "problem.pddl", box)
    assert failure.kind is FailureKind.OBSTRUCTED and failure.objects[0] == blocker


def test_sort_clutter_a_target_in_the_row_is_obstructed_by_its_neighbours() -> None:
    failure = _first_failing_pick(BENCHMARKS / "sort_clutter" / "problem.pddl", "blue2")
    assert failure.kind is FailureKind.OBSTRUCTED
    neighbours = {"red1", "red2", "clutter2", "clutter3", "clutter6", "clutter7"}
    assert set(failure.objects[:2]) <= neighbours
