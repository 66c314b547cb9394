"""The real IPC problems of ``benchmarks/ipc/``: the default GBFS solves each with a valid plan.

One problem of each of the fifteen domains runs in the quick loop; the larger ones (and mystery-10,
36 738 ground actions) are marked slow. ``benchmarks/symbolic.py --ipc`` times all of them.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import greedy_best_first_search, load_task, validate_plan

IPC = Path(__file__).resolve().parents[2] / "benchmarks" / "ipc"

QUICK = [
    ("transport", "task01.pddl"), ("transport", "task04.pddl"), ("elevators", "task01.pddl"),
    ("elevators", "task03.pddl"), ("scanalyzer", "task01.pddl"), ("sokoban", "task01.pddl"),
    ("woodworking", "task05.pddl"), ("woodworking", "task30.pddl"), ("pegsol", "task13.pddl"),
    ("openstacks", "task08.pddl"), ("logistics", "task13.pddl"), ("depot", "task13.pddl"),
    ("rovers", "task08.pddl"), ("satellite", "task08.pddl"), ("freecell", "task03.pddl"),
    ("tpp", "task13.pddl"), ("zenotravel", "task08.pddl"),
]
SLOW = [("mystery", "instance-10.pddl"), ("mystery", "instance-19.pddl"), ("sokoban", "task23.pddl"),
        ("pegsol", "task23.pddl"), ("depot", "task03.pddl"), ("satellite", "task13.pddl")]


def _domain_of(folder: Path, problem: str) -> Path:
    own = folder / ("domain" + problem.removeprefix("task"))  # openstacks: one domain file per problem
    return own if problem.startswith("task") and own.exists() else folder / "domain.pddl"


@pytest.mark.parametrize(("domain", "problem"),
                         QUICK + [pytest.param(*row, marks=pytest.mark.slow) for row in SLOW])
def test_gbfs_solves_the_ipc_problem_with_a_valid_plan(domain: str, problem: str) -> None:
    task = load_task(IPC / domain / problem, _domain_of(IPC / domain, problem))
    # Generous: every one of them takes fewer than 5 000 expansions (sokoban-23: about 4 500).
    result = greedy_best_first_search(task, max_expansions=10_000)
    assert result.solved and result.plan is not None, result.message
    assert validate_plan(task, result.plan).valid
