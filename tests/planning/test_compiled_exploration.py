"""The compiled exploration gives exactly the Python one's h_add costs, supporters, plans and helpful actions.

On the states of seeded random walks in several IPC problems (and the kitchen), and through the greedy
search: with the kernels from the first evaluation, ``gbfs`` returns the same plan after the same counts.
"""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.planning import landmark_count as landmark_count_module
from kitchen_tamp.planning import load_task
from kitchen_tamp.planning.compiled_exploration import BUCKET_LEVELS, CompiledExploration
from kitchen_tamp.planning.heuristics import RelaxedExploration
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.search.alternating_greedy import alternating_greedy_search
from kitchen_tamp.planning.search.random_walks import random_walk_states
from kitchen_tamp.planning.search.result import SearchBudget
from kitchen_tamp.planning.task import State, Task
from tests.planning.conftest import KITCHEN, REPO

IPC = REPO / "benchmarks" / "ipc"

PROBLEMS = [("depot", "task03.pddl"), ("sokoban", "task23.pddl"), ("rovers", "task08.pddl"),
            ("transport", "task04.pddl"), ("pegsol", "task13.pddl"), ("woodworking", "task05.pddl"),
            ("tpp", "task13.pddl"), ("freecell", "task03.pddl")]


def _load(domain: str, problem: str) -> Task:
    return load_task(IPC / domain / problem, IPC / domain / "domain.pddl")


Answer = tuple[list[float], list[int], list[int], int]


def _python_answer(exploration: RelaxedExploration, state: State) -> Answer | None:
    explored = exploration.additive_costs(state)
    if explored is None:
        return None
    cost, supporter = explored
    plan = exploration.supported_plan(cost, supporter, exploration.goal_ids)
    pre = exploration.pre_masks
    helpful = sum(1 << action for action in plan if pre[action] & state == pre[action])
    return cost, supporter, plan, helpful


@pytest.mark.parametrize("bucket_levels", [BUCKET_LEVELS, 1, 3])
@pytest.mark.parametrize(("domain", "problem"), PROBLEMS)
def test_costs_supporters_plans_and_helpful_actions_equal_pythons(domain: str, problem: str,
                                                                  bucket_levels: int) -> None:
    """With every cost in a bucket, and with the dearer ones in the heap (from cost 1, from cost 3)."""
    task = _load(domain, problem)
    exploration = RelaxedExploration(task, "hadd")
    compiled = CompiledExploration(exploration, bucket_levels=bucket_levels)
    dead_ends = 0
    for state in random_walk_states(task, seed=len(task.actions), walks=12, length=25):
        expected = _python_answer(exploration, state)
        state_array = compiled.explore(state)
        assert (state_array is None) == (expected is None)
        if expected is None or state_array is None:
            dead_ends += 1
            continue
        cost, supporter, plan, helpful = expected
        assert compiled.costs() == cost
        assert compiled.supporters() == supporter
        length, compiled_helpful = compiled.plan_and_helpful(state_array)
        assert compiled.plan[:length].tolist() == plan
        assert compiled_helpful == helpful
        # A relaxed plan to other targets (the landmark count's nearest landmarks) as well.
        targets = [atom for atom in range(len(task.atoms)) if cost[atom] == 2][:5]
        length, _ = compiled.plan_and_helpful(state_array, np.array(targets, dtype=np.int64))
        assert compiled.plan[:length].tolist() == exploration.supported_plan(cost, supporter, targets)
    if domain == "sokoban":
        assert dead_ends, "the walks meet sokoban's dead ends"


@pytest.mark.parametrize(("domain", "problem"), PROBLEMS)
def test_evaluations_with_the_kernels_equal_pythons(domain: str, problem: str) -> None:
    """h_FF, h_LM and the preferred operators (helpful, landmark achievers, towards the nearest landmarks)."""
    task = _load(domain, problem)
    python = LandmarkEvaluator(RelaxedExploration(task, "hadd"))
    python.compiled_after_work = 10**18
    compiled = LandmarkEvaluator(RelaxedExploration(task, "hadd"))
    compiled.compiled_after_work = -1
    assert python.count is not None
    accepted = python.count.accepted_at_start(task.initial_state)
    towards_nearest = 0
    for state in random_walk_states(task, seed=len(task.atoms), walks=12, length=25):
        expected = python.evaluate(state, accepted)
        assert compiled.evaluate(state, accepted) == expected
        _, next_up = python.count.value(state, accepted)
        towards_nearest += bool(next_up) and not python.count.achieving_actions(state, next_up)
        accepted = python.count.accepted_after(accepted, state)
    assert compiled.compiled is not None and python.compiled is None
    if domain == "rovers":
        assert towards_nearest, "the walks reach states where no landmark achiever applies"


def test_a_goal_state_has_an_empty_plan_and_no_helpful_actions() -> None:
    task = _load("depot", "task13.pddl")
    goal_state = task.initial_state | task.goal
    compiled = CompiledExploration(RelaxedExploration(task, "hadd"))
    state_array = compiled.explore(goal_state)
    assert state_array is not None
    assert compiled.plan_and_helpful(state_array) == (0, 0)


@pytest.mark.parametrize(("domain", "problem"), [("depot", "task13.pddl"), ("sokoban", "task01.pddl"),
                                                 ("elevators", "task03.pddl"), ("kitchen", "")])
def test_greedy_search_finds_the_same_plan_with_the_kernels(domain: str, problem: str,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    task = (load_task(KITCHEN / "problem.pddl", KITCHEN / "domain.pddl") if domain == "kitchen"
            else _load(domain, problem))
    python = alternating_greedy_search(task, SearchBudget(None, 20_000))
    monkeypatch.setattr(landmark_count_module, "COMPILED_AFTER_WORK", -1)
    compiled = alternating_greedy_search(task, SearchBudget(None, 20_000))
    assert python.solved
    assert (compiled.plan, compiled.expanded, compiled.generated, compiled.evaluated) == (
        python.plan, python.expanded, python.generated, python.evaluated)


def test_the_evaluator_switches_to_the_kernels_only_after_enough_work() -> None:
    small = load_task(KITCHEN / "problem.pddl", KITCHEN / "domain.pddl")
    evaluator = LandmarkEvaluator(RelaxedExploration(small, "hadd"))
    evaluator.root()
    assert evaluator.compiled is None
    assert evaluator.work_per_evaluation * 1000 < landmark_count_module.COMPILED_AFTER_WORK
    large = _load("depot", "task03.pddl")
    evaluator = LandmarkEvaluator(RelaxedExploration(large, "hadd"))
    evaluator.compiled_after_work = 40 * evaluator.work_per_evaluation
    states = random_walk_states(large, seed=3, walks=12, length=25)
    for evaluated, state in enumerate(states[:40], start=1):
        evaluator.child(state, 0)
        assert evaluator.compiled is None, evaluated
    evaluator.child(states[40], 0)
    assert evaluator.compiled is not None and evaluator.compiled_count is not None
