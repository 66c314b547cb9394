"""Fixtures for kitchen tests: problems on disk and kitchens built from them (DIRECT,
always closed)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from kitchen_tamp.kitchen import KitchenScene, build_kitchen_for_task
from kitchen_tamp.planning import Task, load_task

REPO = Path(__file__).resolve().parents[2]
DOMAIN = REPO / "pddl" / "domain.pddl"
PROBLEMS = Path(__file__).resolve().parent / "problems"

LAYOUT_PROBLEMS = [
    REPO / "pddl" / "problem.pddl",
    REPO / "pddl" / "problem_hard.pddl",
    PROBLEMS / "sugar_in_closed_drawer.pddl",
    PROBLEMS / "open_drawer_spam_inside.pddl",
    PROBLEMS / "both_on_stove.pddl",
]


def task_of(problem: Path) -> Task:
    return load_task(problem, DOMAIN)


@pytest.fixture
def build() -> Iterator[Callable[[Path], KitchenScene]]:
    """Build kitchens for problem files; all are closed after the test."""
    built: list[KitchenScene] = []

    def make(problem: Path) -> KitchenScene:
        kitchen = build_kitchen_for_task(task_of(problem))
        built.append(kitchen)
        return kitchen

    yield make
    for kitchen in built:
        kitchen.close()
        assert not kitchen.scene.connected
