"""Whole plans of the repository's problems: every step finds targets and the goal holds."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import abstract_state, build_kitchen_for_task, sample_action_targets
from kitchen_tamp.planning import plan
from tests.kitchen.conftest import LAYOUT_PROBLEMS, task_of

pytestmark = pytest.mark.slow  # each test runs or replays a whole kitchen pipeline


@pytest.mark.parametrize("problem", LAYOUT_PROBLEMS, ids=lambda p: p.stem)
@pytest.mark.parametrize("seed", [0, 1])
def test_plan_reaches_the_goal(problem: Path, seed: int) -> None:
    task = task_of(problem)
    steps = plan(task, "bfs").plan
    assert steps is not None
    rng = np.random.default_rng(seed)
    with build_kitchen_for_task(task) as kitchen:
        for action in steps:
            sample_action_targets(kitchen, action, rng).apply(kitchen)
        assert task.goal_atoms <= abstract_state(kitchen)
