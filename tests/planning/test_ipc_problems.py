"""The real IPC problems of ``benchmarks/ipc/``: the default GBFS solves each with a valid plan."""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import greedy_best_first_search, load_task, validate_plan

IPC = Path(__file__).resolve().parents[2] / "benchmarks" / "ipc"

PROBLEMS = [
    ("transport", "task01.pddl"), ("transport", "task04.pddl"), ("elevators", "task01.pddl"),
    ("elevators", "task03.pddl"), ("scanalyzer", "task01.pddl"), ("sokoban", "task01.pddl"),
    pytest.param("mystery", "instance-10.pddl", marks=pytest.mark.slow),  # 36 738 ground actions
]


@pytest.mark.parametrize(("domain", "problem"), PROBLEMS)
def test_gbfs_solves_the_ipc_problem_with_a_valid_plan(domain: str, problem: str) -> None:
    task = load_task(IPC / domain / problem, IPC / domain / "domain.pddl")
    # Generous: every one of them takes fewer than 500 expansions (mystery-10: 54).
    result = greedy_best_first_search(task, max_expansions=5000)
    assert result.solved and result.plan is not None, result.message
    assert validate_plan(task, result.plan).valid
