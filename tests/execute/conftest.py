"""The kitchen plan the execute tests replay and doctor: problem.pddl, rrt, seed 0, refined
once per test session (``tests/conftest.py``), and the judge's verdict on it."""

from __future__ import annotations

import pytest

from kitchen_tamp.execute import Verification, verify_trajectory
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task
from tests.conftest import PDDL, KitchenRuns

PROBLEM = PDDL / "problem.pddl"


@pytest.fixture(scope="session")
def kitchen_task(kitchen_runs: KitchenRuns) -> Task:
    return kitchen_runs.refined().task


@pytest.fixture(scope="session")
def refined(kitchen_runs: KitchenRuns) -> KitchenTrajectory:
    return kitchen_runs.refined().trajectory


@pytest.fixture(scope="session")
def verified(kitchen_task: Task, refined: KitchenTrajectory) -> Verification:
    """The judge's verdict on the refined plan, with its replay of every segment."""
    with build_kitchen_for_task(kitchen_task) as kitchen:
        return verify_trajectory(kitchen, kitchen_task, refined)
