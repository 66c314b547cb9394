from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import Task, load_task

DATA = Path(__file__).parent / "data"
REPO = Path(__file__).resolve().parents[2]
KITCHEN = REPO / "pddl"


def data_task(problem: str, domain: str) -> Task:
    return load_task(DATA / problem, DATA / domain)


def written_task(tmp_path: Path, domain_text: str, domain_name: str, problem_name: str,
                 objects: list[str], facts: list[str], goal: str) -> Task:
    """Write a generated problem and its domain into ``tmp_path`` and load them."""
    problem = (f"(define (problem {problem_name}) (:domain {domain_name}) (:objects {' '.join(objects)})\n"
               f"  (:init {' '.join(facts)})\n  (:goal {goal}))\n")
    (tmp_path / "domain.pddl").write_text(domain_text)
    (tmp_path / "problem.pddl").write_text(problem)
    return load_task(tmp_path / "problem.pddl", tmp_path / "domain.pddl")


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
