from __future__ import annotations

import pytest

from kitchen_tamp.planning import SEARCHES, Task, plan, validate_plan
from tests.planning.brute_force import shortest_plan_length
from tests.planning.conftest import data_task


@pytest.mark.parametrize("planner", sorted(SEARCHES))
def test_every_search_returns_a_valid_plan(small_task: Task, planner: str) -> None:
    result = plan(small_task, planner)
    if planner == "ehc" and small_task.name == "tempting":
        assert result.status == "failed"
        return
    assert result.status == "solved", result.message
    assert result.plan is not None
    assert validate_plan(small_task, result.plan).valid


@pytest.mark.parametrize("planner", ["bfs", "astar"])
def test_optimal_searches_match_brute_force(small_task: Task, planner: str) -> None:
    result = plan(small_task, planner)
    assert result.plan is not None
    assert len(result.plan) == shortest_plan_length(small_task)


def test_kitchen_plans_have_the_known_optimal_lengths() -> None:
    from kitchen_tamp.planning import load_task
    from tests.planning.conftest import SMALL_TASKS

    assert len(plan(load_task(*SMALL_TASKS["kitchen"]), "bfs").plan or ()) == 5
    hard = load_task(*SMALL_TASKS["kitchen_hard"])
    result = plan(hard, "astar")
    assert result.plan is not None and len(result.plan) == 7
    # The swap needs the drawer as a temporary place.
    assert any(action.name == "placeIn" for action in result.plan)


@pytest.mark.parametrize("planner", ["bfs", "gbfs", "astar"])
def test_complete_searches_prove_unsolvability(planner: str) -> None:
    task = data_task("delivery_unsolvable.pddl", "delivery_domain.pddl")
    result = plan(task, planner)
    assert result.status == "unsolvable"
    assert result.plan is None
    assert result.message.startswith("unsolvable:")


@pytest.mark.parametrize("planner", sorted(SEARCHES))
def test_a_false_static_goal_is_unsolvable_before_search(planner: str) -> None:
    task = data_task("delivery_unreachable_goal.pddl", "delivery_domain.pddl")
    assert task.trivially_unsolvable
    result = plan(task, planner)
    assert result.status == "unsolvable"
    assert "(road north depot)" in result.message
    assert result.expanded == 0


def test_enforced_hill_climbing_reports_a_dead_end_instead_of_hanging() -> None:
    task = data_task("dead_end_problem.pddl", "dead_end_domain.pddl")
    result = plan(task, "ehc")
    assert result.status == "failed"
    assert "dead end" in result.message
    assert len(plan(task, "bfs").plan or ()) == 4  # the detour exists


def test_enforced_hill_climbing_breaks_ties_first_in_first_out() -> None:
    # In the kitchen the first action has several children with the same h; the
    # first generated (open drawer comes first in the domain) must win.
    task = data_task("../../../pddl/problem.pddl", "../../../pddl/domain.pddl")
    first = plan(task, "ehc").plan
    assert first is not None and str(first[0]) == "open drawer"


@pytest.mark.parametrize("planner", sorted(SEARCHES))
def test_a_goal_that_already_holds_gives_the_empty_plan(planner: str, tmp_path: object) -> None:
    from pathlib import Path

    from kitchen_tamp.planning import load_task
    from tests.planning.conftest import KITCHEN

    problem = Path(str(tmp_path)) / "done.pddl"
    problem.write_text(
        "(define (problem done) (:domain kitchen)"
        " (:objects stove - surface sugar - box)"
        " (:init (boxOn sugar stove) (armClear)) (:goal (boxOn sugar stove)))")
    result = plan(load_task(problem, KITCHEN / "domain.pddl"), planner)
    assert result.status == "solved" and result.plan == ()


@pytest.mark.parametrize("planner", sorted(SEARCHES))
def test_expansion_budget_is_respected(planner: str) -> None:
    task = data_task("blocks_tower4.pddl", "blocks_domain.pddl")
    result = plan(task, planner, max_expansions=2)
    assert result.status == "budget"
    assert result.expanded <= 2
    assert result.plan is None


def test_searches_are_deterministic(small_task: Task) -> None:
    for planner in SEARCHES:
        assert plan(small_task, planner).plan == plan(small_task, planner).plan


def test_unknown_planner_is_rejected() -> None:
    task = data_task("blocks_sussman.pddl", "blocks_domain.pddl")
    with pytest.raises(ValueError, match="unknown planner"):
        plan(task, "dijkstra")


def test_enforced_hill_climbing_retries_with_every_action_when_helpful_ones_fail() -> None:
    task = data_task("helpful_trap_problem.pddl", "helpful_trap_domain.pddl")
    result = plan(task, "ehc")
    assert result.status == "solved", result.message
    assert [str(a) for a in result.plan or ()] == ["prepare", "finish-prepared"]


@pytest.mark.parametrize("guided", [True, False])
def test_greedy_searches_with_and_without_helpful_actions_find_valid_plans(
        small_task: Task, guided: bool) -> None:
    from kitchen_tamp.planning import enforced_hill_climbing, greedy_best_first_search

    greedy = greedy_best_first_search(small_task, preferred_operators=guided)
    assert greedy.status == "solved" and greedy.plan is not None
    assert validate_plan(small_task, greedy.plan).valid
    climbing = enforced_hill_climbing(small_task, helpful_actions=guided)
    assert climbing.status in ("solved", "failed")  # "failed": a dead end, as in the trap
    if climbing.plan is not None:
        assert validate_plan(small_task, climbing.plan).valid


def test_helpful_actions_cut_enforced_hill_climbing_on_blocks() -> None:
    from kitchen_tamp.planning import enforced_hill_climbing

    task = data_task("blocks_tower4.pddl", "blocks_domain.pddl")
    guided = enforced_hill_climbing(task)
    plain = enforced_hill_climbing(task, helpful_actions=False)
    assert guided.solved and plain.solved
    assert guided.evaluated <= plain.evaluated


def test_preferred_operator_search_proves_unsolvability_too() -> None:
    from kitchen_tamp.planning import greedy_best_first_search

    task = data_task("delivery_unsolvable.pddl", "delivery_domain.pddl")
    result = greedy_best_first_search(task, preferred_operators=True)
    assert result.status == "unsolvable"
