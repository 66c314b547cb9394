"""The shortcut's compiled steps (used when the checker is the sphere model): the same paths, tries,
shortcuts and checks as its Python steps from the same seed, and paths free for Drake."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.motion import (
    RrtConnectHyperparameters,
    ShortcutHyperparameters,
    densify_path,
    path_length,
    plan_rrt_connect,
    shortcut_path,
)
from kitchen_tamp.motion.joint_path import JointPath
from tests.motion.test_compiled_rrt_connect import SPACE, PythonLoopSpheres


def _raw_path(mbm_table: Any, seed: int) -> JointPath:
    problem, spheres, _ = mbm_table
    search = RrtConnectHyperparameters(step_size=0.3)  # many short edges: much for the shortcut to do
    start, goal = problem.start, problem.goals[0]
    planned = plan_rrt_connect(start, goal, SPACE, spheres, search, seed=seed, time_budget_s=math.inf)
    return planned.require_path()


@pytest.mark.parametrize(
    ("seed", "settings"),
    [
        (0, ShortcutHyperparameters()),
        (1, ShortcutHyperparameters()),
        (2, ShortcutHyperparameters(max_unsuccessful_tries=None, max_iterations=99, corner_cutting_passes=2)),
        (3, ShortcutHyperparameters(connect_furthest_vertices=False, min_gain_per_length=0.0)),
    ],
)
def test_the_compiled_steps_shorten_as_the_python_steps_do(
    mbm_table: Any, seed: int, settings: ShortcutHyperparameters
) -> None:
    _, spheres, _ = mbm_table
    raw = _raw_path(mbm_table, seed)
    compiled = shortcut_path(raw, spheres, settings, seed=seed, time_budget_s=math.inf)
    python = shortcut_path(raw, PythonLoopSpheres(spheres), settings, seed=seed, time_budget_s=math.inf)
    assert compiled.shortcuts_taken > 0 and compiled.collision_checks > 0
    assert (compiled.iterations, compiled.shortcuts_taken, compiled.collision_checks) == (
        python.iterations,
        python.shortcuts_taken,
        python.collision_checks,
    )
    np.testing.assert_array_equal(compiled.path, python.path)


def test_compiled_shortcuts_are_free_for_drake_and_shorter(mbm_table: Any) -> None:
    _, spheres, exact = mbm_table
    raw = _raw_path(mbm_table, 4)
    smoothed = shortcut_path(raw, spheres, seed=4, time_budget_s=math.inf).path
    np.testing.assert_array_equal(smoothed[[0, -1]], raw[[0, -1]])
    assert path_length(smoothed) < path_length(raw)
    assert np.all(exact.is_valid(densify_path(smoothed, JUDGE_RESOLUTION_RAD)))
