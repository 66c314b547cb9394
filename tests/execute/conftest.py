"""A kitchen plan refined once per test session (problem.pddl, seed 0), shared by the
execute tests, which replay and tamper with copies of it."""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.execute import Verification, verify_trajectory
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task, load_task
from kitchen_tamp.refinement import SamplingMotionBackend, refine_with_sesame

REPO = Path(__file__).resolve().parents[2]
PROBLEM = REPO / "pddl" / "problem.pddl"


@pytest.fixture(scope="session")
def kitchen_task() -> Task:
    return load_task(PROBLEM)


@pytest.fixture(scope="session")
def refined(kitchen_task: Task) -> KitchenTrajectory:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        refined = refine_with_sesame(kitchen, kitchen_task, SamplingMotionBackend(), seed=0).refined
    assert refined is not None
    return refined.trajectory


@pytest.fixture(scope="session")
def verified(kitchen_task: Task, refined: KitchenTrajectory) -> Verification:
    """The judge's verdict on the refined plan, with its replay of every segment."""
    with build_kitchen_for_task(kitchen_task) as kitchen:
        return verify_trajectory(kitchen, kitchen_task, refined)
