"""SeSamE and its two small-budget forms on scenes built for each behaviour."""

from __future__ import annotations

from dataclasses import replace

import pytest

from kitchen_tamp.bilevel import (
    Outcome,
    PlanningCounts,
    SampleEvent,
    SesameBudgets,
    backtracking_refinement,
    greedy_refinement,
    sesame,
)
from kitchen_tamp.bilevel.toy_rooms import (
    blocked_doorway,
    no_door_to_goal,
    open_corridor,
    pillar_shadow,
    point,
    walled_off,
)
from tests.bilevel.chain_problem import chain_problem
from tests.bilevel.valid_plans import assert_valid_toy_plan


def test_greedy_refinement_succeeds_where_every_sample_works() -> None:
    scene = open_corridor()
    problem = scene.problem()
    for seed in range(5):
        result = greedy_refinement(problem, seed=seed)
        assert result.outcome is Outcome.SOLVED
        assert result.counts.samples == 2 and result.counts.failures == 0
        assert_valid_toy_plan(scene, problem, result.plan)


def test_greedy_fails_in_the_pillar_shadow_where_backtracking_succeeds() -> None:
    scene = pillar_shadow()
    problem = scene.problem()
    greedy = greedy_refinement(problem, seed=1)
    assert not greedy.solved
    first_step, second_step = greedy.attempts[0].steps
    assert (first_step.samples, first_step.failures) == (1, 0)  # landed in B ...
    assert (second_step.samples, second_step.failures) == (1, 1)  # ... where door B-C is hidden
    assert second_step.last_failure is not None and "pillar" in second_step.last_failure
    assert greedy.counts.backtracks == 0

    backtracking = backtracking_refinement(problem, seed=1)
    assert backtracking.solved and backtracking.counts.backtracks >= 1
    assert_valid_toy_plan(scene, problem, backtracking.plan)


def test_the_pillar_shadow_defeats_greedy_for_most_seeds_and_backtracking_for_none() -> None:
    problem = pillar_shadow().problem()
    seeds = range(20)
    assert sum(greedy_refinement(problem, seed=seed).solved for seed in seeds) <= 8
    assert all(backtracking_refinement(problem, seed=seed).solved for seed in seeds)


def test_sesame_switches_to_the_second_abstract_plan_when_the_first_is_blocked() -> None:
    scene = blocked_doorway()
    problem = scene.problem()
    result = sesame(problem, seed=0)
    assert result.solved and result.counts.abstract_plans == 2
    first, second = result.attempts
    assert first.abstract_plan.states == ("A", "B", "C")
    assert first.outcome is Outcome.STEPS_EXHAUSTED and "crate in B-C" in first.detail
    assert second.refined and second.abstract_plan.states == ("A", "D", "E", "F", "C")
    assert result.plan is not None and result.plan.abstract_plan == second.abstract_plan
    assert_valid_toy_plan(scene, problem, result.plan)

    for single_plan in (greedy_refinement(problem, seed=0), backtracking_refinement(problem, seed=0)):
        assert not single_plan.solved
        assert single_plan.outcome is Outcome.PLAN_BUDGET and single_plan.counts.abstract_plans == 1


def test_backtracking_tries_k_samples_per_step_before_stepping_back() -> None:
    k = 4
    problem = chain_problem(2, lambda action, _: action == "s1->s2")
    result = backtracking_refinement(problem, SesameBudgets(samples_per_step=k), seed=0)
    (attempt,) = result.attempts
    first, second = attempt.steps
    assert (first.samples, first.failures, first.backtracks) == (k, 0, k - 1)
    assert (second.samples, second.failures, second.backtracks) == (k * k, k * k, 0)
    assert result.counts == PlanningCounts(k + k * k, failures=k * k, backtracks=k - 1, abstract_plans=1)
    assert attempt.outcome is Outcome.STEPS_EXHAUSTED
    assert "step 2 (s1->s2) last failed: s1->s2 refused sample 16" in attempt.detail


# A budget far above what try-counting spends: were successes not counted, a step that always
# succeeds would never give up and these runs would end on SAMPLE_BUDGET instead.
_GENEROUS_MAX_SAMPLES = 10_000


@pytest.mark.parametrize("length", [1, 2, 3])
@pytest.mark.parametrize("k", [1, 2, 3])
def test_a_dead_end_costs_k_plus_k_squared_up_to_k_to_the_n_samples(length: int, k: int) -> None:
    # every step succeeds except the last, which always fails: each success enters the next step afresh
    problem = chain_problem(length, lambda action, _: action == f"s{length - 1}->s{length}")
    budgets = SesameBudgets(samples_per_step=k, max_samples=_GENEROUS_MAX_SAMPLES)
    result = backtracking_refinement(problem, budgets, seed=0)
    (attempt,) = result.attempts
    assert attempt.outcome is Outcome.STEPS_EXHAUSTED
    assert [step.samples for step in attempt.steps] == [k ** (i + 1) for i in range(length)]
    assert result.counts.samples == sum(k ** (i + 1) for i in range(length))


def test_a_step_gives_up_after_k_tries_since_entered_successes_included() -> None:
    k = 3
    # step 1 always succeeds, step 2 refuses its odd-numbered samples, step 3 always fails
    problem = chain_problem(
        3, lambda action, sample: action == "s2->s3" or (action == "s1->s2" and sample % 2 == 1))
    events: list[SampleEvent[str, str]] = []
    budgets = SesameBudgets(max_plans=1, samples_per_step=k, max_samples=_GENEROUS_MAX_SAMPLES)
    result = sesame(problem, budgets, seed=0, on_sample=events.append)
    assert result.outcome is Outcome.PLAN_BUDGET
    dead_end = [(3, False)] * k
    expected = [
        # step 2's first visit: refused, accepted (step 3 gives up), refused: three tries, two failures
        (1, True), (2, False), (2, True), *dead_end, (2, False),
        # step 1 again; step 2 is entered afresh with three tries, two of them accepted
        (1, True), (2, True), *dead_end, (2, False), (2, True), *dead_end,
        (1, True), (2, False), (2, True), *dead_end, (2, False),
    ]  # step 1 has had its three tries: the plan is abandoned
    assert [(e.step_index + 1 if e.step_index is not None else 0, e.succeeded) for e in events] == expected
    first, second, third = result.attempts[0].steps
    assert (first.samples, first.failures, first.backtracks) == (k, 0, k - 1)
    assert (second.samples, second.failures) == (3 * k, 5)
    assert (third.samples, third.failures) == (4 * k, 4 * k)


def test_backtracking_goes_back_as_far_as_needed() -> None:
    k = 2
    # the third step fails 3k times: from both states of the first visit of step 2, then once more
    problem = chain_problem(3, lambda action, sample: action == "s2->s3" and sample <= 3 * k)
    result = backtracking_refinement(problem, SesameBudgets(samples_per_step=k), seed=0)
    assert result.solved
    first, second, third = result.attempts[0].steps
    assert third.failures == 3 * k and third.samples == 3 * k + 1
    assert (second.samples, second.backtracks) == (2 * k, 2)
    assert (first.samples, first.backtracks) == (2, 1)


def test_greedy_never_backtracks() -> None:
    result = greedy_refinement(chain_problem(3, lambda action, _: action == "s2->s3"), seed=0)
    assert result.counts == PlanningCounts(samples=3, failures=1, backtracks=0, abstract_plans=1)


def test_every_planner_fails_when_the_goal_is_walled_off() -> None:
    problem = walled_off().problem()
    result = sesame(problem, seed=0)
    assert result.outcome is Outcome.NO_ABSTRACT_PLAN and result.plan is None
    assert not greedy_refinement(problem, seed=0).solved
    assert not backtracking_refinement(problem, seed=0).solved


def test_no_abstract_plan_means_no_sample() -> None:
    result = sesame(no_door_to_goal().problem(), seed=0)
    assert result.outcome is Outcome.NO_ABSTRACT_PLAN
    assert result.counts.samples == 0 and result.counts.abstract_plans == 0


def test_a_start_in_the_goal_is_the_empty_plan() -> None:
    problem = open_corridor().problem()
    at_goal = replace(problem, initial_state=point(2.5, 0.5))
    result = sesame(at_goal, seed=0)
    assert result.solved and result.plan is not None and result.plan.steps == ()
    assert result.counts.samples == 0


def test_invalid_budgets_are_refused() -> None:
    problem = open_corridor().problem()
    with pytest.raises(ValueError, match="samples_per_step"):
        sesame(problem, SesameBudgets(samples_per_step=0))
    with pytest.raises(ValueError, match="max_plans"):
        sesame(problem, SesameBudgets(max_plans=0))
