"""The sweep grid: seed ranges, task ids and the expansion of problems x modes x seeds."""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.evaluate.grid import GridError, TaskSpec, expand_grid, parse_seeds
from kitchen_tamp.evaluate.problem_sets import problem_set


def test_seed_ranges_expand_in_order_without_repeats() -> None:
    assert parse_seeds("0-3") == (0, 1, 2, 3)
    assert parse_seeds("7") == (7,)
    assert parse_seeds("0-2, 10,1-3") == (0, 1, 2, 10, 3)


@pytest.mark.parametrize("text", ["", "a", "3-1", "-1", "1-", "0-x", "2--3"])
def test_bad_seed_ranges_are_refused(text: str) -> None:
    with pytest.raises(GridError, match="seed range"):
        parse_seeds(text)


def test_grid_is_every_problem_mode_and_seed_once() -> None:
    problems = [Path("/p/problem.pddl"), Path("/p/problem_hard.pddl"), Path("/p/problem.pddl")]
    tasks = expand_grid(problems, ["rrt", "optimizes", "rrt"], [0, 1, 1])
    assert len(tasks) == 2 * 2 * 2
    assert len({t.task_id for t in tasks}) == len(tasks)
    assert tasks[0] == TaskSpec(Path("/p/problem.pddl"), "rrt", 0)
    assert tasks[0].task_id == "problem-rrt-seed0"
    assert [t.problem.stem for t in tasks] == ["problem"] * 4 + ["problem_hard"] * 4
    expected = {("rrt", 0), ("rrt", 1), ("optimizes", 0), ("optimizes", 1)}
    assert {(t.mode, t.seed) for t in tasks[:4]} == expected


def test_problems_with_one_name_in_two_folders_are_refused() -> None:
    with pytest.raises(GridError, match="both named 'problem'"):
        expand_grid([Path("/a/problem.pddl"), Path("/b/problem.pddl")], ["rrt"], [0])


def test_unknown_modes_are_refused() -> None:
    with pytest.raises(GridError, match="unknown mode 'prm'"):
        expand_grid([Path("/a/problem.pddl")], ["prm"], [0])


def test_a_problem_set_names_its_problems_and_the_names_make_the_task_ids() -> None:
    named = problem_set("benchmarks")
    names = sorted(named.values())
    assert names == ["blocked", "kitchen", "kitchen-radish", "nonmonotonic", "packed", "sort_clutter",
                     "towers-reversal", "towers-sussman"]
    assert all(path.is_file() and path.parent.parent.name == "benchmarks" for path in named)
    tasks = expand_grid(list(named), ["rrt"], [3], named)
    assert {task.task_id for task in tasks} >= {"towers-sussman-rrt-seed3", "blocked-rrt-seed3"}
    with pytest.raises(ValueError, match="unknown problem set 'ipc'"):
        problem_set("ipc")
