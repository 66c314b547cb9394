"""A kitchen plan refined once per test session (problem.pddl, seed 0), shared by the
execute tests, which replay and tamper with copies of it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task, load_task, plan
from kitchen_tamp.refinement import SamplingMotionBackend, refine_plan

REPO = Path(__file__).resolve().parents[2]
PROBLEM = REPO / "pddl" / "problem.pddl"


@pytest.fixture(scope="session")
def kitchen_task() -> Task:
    return load_task(PROBLEM)


@pytest.fixture(scope="session")
def refined(kitchen_task: Task) -> KitchenTrajectory:
    result = plan(kitchen_task, "bfs")
    assert result.plan is not None
    with build_kitchen_for_task(kitchen_task) as kitchen:
        refined = refine_plan(kitchen, result.plan, SamplingMotionBackend(), np.random.default_rng(0))
    return refined.trajectory
