from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import Task, load_task

DATA = Path(__file__).parent / "data"
REPO = Path(__file__).resolve().parents[2]
KITCHEN = REPO / "pddl"


def data_task(problem: str, domain: str) -> Task:
    return load_task(DATA / problem, DATA / domain)


SMALL_TASKS = {
    "kitchen": (KITCHEN / "problem.pddl", KITCHEN / "domain.pddl"),
    "kitchen_hard": (KITCHEN / "problem_hard.pddl", KITCHEN / "domain.pddl"),
    "sussman": (DATA / "blocks_sussman.pddl", DATA / "blocks_domain.pddl"),
    "tower4": (DATA / "blocks_tower4.pddl", DATA / "blocks_domain.pddl"),
    "delivery": (DATA / "delivery_two_parcels.pddl", DATA / "delivery_domain.pddl"),
    "trap": (DATA / "dead_end_problem.pddl", DATA / "dead_end_domain.pddl"),
}


@pytest.fixture(params=sorted(SMALL_TASKS))
def small_task(request: pytest.FixtureRequest) -> Task:
    problem, domain = SMALL_TASKS[request.param]
    return load_task(problem, domain)
