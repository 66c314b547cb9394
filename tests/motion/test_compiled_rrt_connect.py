"""RRT-Connect's compiled loop (used when the checker is the sphere model): the same search as the
Python loop from the same seed, paths free for Drake, the same path for the same seed."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.motion import (
    ConfigurationSpace,
    JointConfiguration,
    JointConfigurations,
    PlanStatus,
    RrtConnectHyperparameters,
    ValidityMask,
    densify_path,
    plan_rrt_connect,
)
from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
from kitchen_tamp.motion.motion_bench_maker import (
    MBM_PANDA_LOWER,
    MBM_PANDA_UPPER,
)
from kitchen_tamp.motion.sampling import compiled_rrt_connect
from kitchen_tamp.motion.segment_checking import CompiledValidity

SPACE = ConfigurationSpace(MBM_PANDA_LOWER, MBM_PANDA_UPPER)


class PythonLoopSpheres:
    """The sphere model without its compiled validity: `plan_rrt_connect` runs its Python loop."""

    def __init__(self, spheres: SphereCollisionChecker) -> None:
        self.spheres = spheres

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        return self.spheres.is_valid(qs)

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return self.spheres.segment_valid(q0, q1)

    def segment_checked(self, *arguments: Any) -> tuple[bool, int]:
        return self.spheres.segment_checked(*arguments)

    def free_prefix_checked(self, *arguments: Any) -> tuple[float, int]:
        return self.spheres.free_prefix_checked(*arguments)


def test_the_sphere_model_offers_its_compiled_validity(mbm_table: Any) -> None:
    _, spheres, _ = mbm_table
    assert isinstance(spheres, CompiledValidity) and spheres.compiled_validity() is not None
    assert not isinstance(PythonLoopSpheres(spheres), CompiledValidity)


@pytest.mark.parametrize(("seed", "tree_balance"), [(0, 0.0), (1, 0.0), (2, 0.0), (0, 1.5), (1, 1.5)])
def test_the_compiled_loop_searches_as_the_python_loop_does(
    mbm_table: Any, seed: int, tree_balance: float
) -> None:
    problem, spheres, _ = mbm_table
    start, goal = problem.start, problem.goals[0]
    search = RrtConnectHyperparameters(tree_balance=tree_balance)
    compiled = plan_rrt_connect(start, goal, SPACE, spheres, search, seed=seed, time_budget_s=math.inf)
    python = plan_rrt_connect(
        start, goal, SPACE, PythonLoopSpheres(spheres), search, seed=seed, time_budget_s=math.inf
    )
    assert compiled.status is PlanStatus.SOLVED and compiled.iterations > 0
    assert (compiled.iterations, compiled.nodes) == (python.iterations, python.nodes)
    assert compiled.collision_checks == python.collision_checks
    np.testing.assert_allclose(compiled.require_path(), python.require_path(), rtol=0.0, atol=1e-12)


def test_the_compiled_loop_searches_alike_across_blocks_and_grown_trees(
    mbm_table: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Blocks of two iterations and trees of 16 rows at first: the search runs over several calls,
    growing the trees between them, and is still the Python loop's."""
    monkeypatch.setattr(compiled_rrt_connect, "BLOCK", 2)
    monkeypatch.setattr(compiled_rrt_connect, "INITIAL_CAPACITY", 16)
    problem, spheres, _ = mbm_table
    start, goal = problem.start, problem.goals[0]
    search = RrtConnectHyperparameters(step_size=0.1)
    compiled = plan_rrt_connect(start, goal, SPACE, spheres, search, seed=5, time_budget_s=math.inf)
    python = plan_rrt_connect(
        start, goal, SPACE, PythonLoopSpheres(spheres), search, seed=5, time_budget_s=math.inf
    )
    assert compiled.status is PlanStatus.SOLVED
    assert compiled.iterations > 2 * 2 and compiled.nodes > 2 * 16  # several calls, grown trees
    assert (compiled.iterations, compiled.nodes) == (python.iterations, python.nodes)
    assert compiled.collision_checks == python.collision_checks
    np.testing.assert_allclose(compiled.require_path(), python.require_path(), rtol=0.0, atol=1e-12)


@pytest.mark.parametrize("seed", [3, 4])
def test_compiled_paths_are_free_for_drake_and_the_same_for_the_same_seed(mbm_table: Any, seed: int) -> None:
    problem, spheres, exact = mbm_table
    start, goal = problem.start, problem.goals[0]
    paths = [
        plan_rrt_connect(start, goal, SPACE, spheres, seed=seed, time_budget_s=math.inf).require_path()
        for _ in range(2)
    ]
    np.testing.assert_array_equal(paths[0], paths[1])
    assert np.allclose(paths[0][0], start) and np.allclose(paths[0][-1], goal)
    assert np.all(exact.is_valid(densify_path(paths[0], JUDGE_RESOLUTION_RAD)))
    assert not np.all(exact.is_valid(densify_path(np.stack([start, goal]), 0.01)))  # a detour


def test_the_compiled_loop_stops_at_its_iteration_limit(mbm_table: Any) -> None:
    problem, spheres, _ = mbm_table
    start, goal = problem.start, problem.goals[0]
    # A seed whose search needs more than one iteration, so that a limit below it leaves trees.
    searches = (
        (seed, plan_rrt_connect(start, goal, SPACE, spheres, seed=seed, time_budget_s=math.inf))
        for seed in range(20)
    )
    seed, needed = next((seed, result.iterations) for seed, result in searches if result.iterations > 1)
    hyperparameters = RrtConnectHyperparameters(max_iterations=needed - 1)
    result = plan_rrt_connect(start, goal, SPACE, spheres, hyperparameters, seed=seed, time_budget_s=math.inf)
    assert result.status is PlanStatus.ITERATION_LIMIT
    assert result.path is None and result.iterations == needed - 1 and result.nodes > 2


def test_the_compiled_ends_and_straight_line_are_the_python_loops(mbm_table: Any) -> None:
    """Ends in collision and a free straight line end the search before the loop, with the same
    status, path and count as through the Python loop's segment checker."""
    problem, spheres, _ = mbm_table
    start, goal = problem.start, problem.goals[0]
    rng = np.random.default_rng(0)
    samples = SPACE.sample_uniform(rng, 400)
    valid = spheres.is_valid(samples)
    colliding = samples[~valid][0]
    near_start = start + 0.05 * (samples[valid][0] - start)  # a short free step from the start
    assert spheres.segment_valid(start, near_start)
    cases = [
        (colliding, goal, PlanStatus.START_IN_COLLISION),
        (start, colliding, PlanStatus.GOAL_IN_COLLISION),
        (start, near_start, PlanStatus.SOLVED),
    ]
    for q0, q1, status in cases:
        compiled = plan_rrt_connect(q0, q1, SPACE, spheres, seed=0, time_budget_s=math.inf)
        python = plan_rrt_connect(q0, q1, SPACE, PythonLoopSpheres(spheres), seed=0, time_budget_s=math.inf)
        assert compiled.status is python.status is status
        assert (compiled.iterations, compiled.nodes) == (python.iterations, python.nodes) == (0, 2)
        assert compiled.collision_checks == python.collision_checks > 0
        if status is PlanStatus.SOLVED:
            np.testing.assert_array_equal(compiled.require_path(), np.stack([q0, q1]))
        else:
            assert compiled.path is None
