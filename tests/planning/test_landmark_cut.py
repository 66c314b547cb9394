"""LM-cut is admissible, at least h_max, and A* with it returns shortest plans."""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import Task, astar_search, breadth_first_search, load_task, validate_plan
from kitchen_tamp.planning.heuristics import RelaxedExploration, make_heuristic
from tests.planning.brute_force import goal_distances, reachable_states

IPC = Path(__file__).resolve().parents[2] / "benchmarks" / "ipc"


def test_lm_cut_is_admissible_and_dominates_h_max(small_task: Task) -> None:
    lm_cut = make_heuristic(small_task, "lmcut")
    exploration = RelaxedExploration(small_task)
    distances = goal_distances(small_task)
    for state in reachable_states(small_task):
        h = lm_cut(state)
        assert h >= exploration.h_max(state)
        if state in distances:
            assert h <= distances[state]
        if small_task.is_goal(state):
            assert h == 0


def test_astar_with_lm_cut_returns_a_shortest_plan(small_task: Task) -> None:
    result = astar_search(small_task)
    shortest = breadth_first_search(small_task)
    assert result.status == shortest.status
    if shortest.plan is not None:
        assert result.plan is not None and len(result.plan) == len(shortest.plan)
        assert validate_plan(small_task, result.plan).valid


@pytest.mark.parametrize(("domain", "problem", "length"), [
    ("transport", "task01.pddl", 5), ("scanalyzer", "task01.pddl", 6), ("woodworking", "task05.pddl", 16),
])
def test_astar_finds_the_length_fast_downward_proves_on_ipc_problems(domain: str, problem: str,
                                                                      length: int) -> None:
    # The lengths Fast Downward's astar(lmcut()) proves optimal (benchmarks/symbolic.py prints both).
    task = load_task(IPC / domain / problem, IPC / domain / "domain.pddl")
    result = astar_search(task, max_expansions=2000)
    assert result.plan is not None and len(result.plan) == length
    assert validate_plan(task, result.plan).valid
