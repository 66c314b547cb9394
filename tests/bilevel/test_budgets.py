"""Every budget is respected: plans, samples (total and per plan), samples per step or transition, time."""

from __future__ import annotations

from kitchen_tamp.bilevel import (
    Outcome,
    SampleEvent,
    SesameBudgets,
    abstract_bfs,
    backtracking_refinement,
    sesame,
)
from kitchen_tamp.bilevel.toy_rooms import Passage, blocked_doorway, nine_rooms, pillar_shadow, walled_off
from tests.bilevel.chain_problem import chain_problem


def test_the_total_sample_budget_stops_sesame() -> None:
    result = sesame(nine_rooms().problem(), SesameBudgets(max_samples=37), seed=0)
    assert result.outcome is Outcome.SAMPLE_BUDGET and not result.solved
    assert result.counts.samples == 37


def test_the_total_sample_budget_stops_abstract_bfs() -> None:
    result = abstract_bfs(nine_rooms().problem(), seed=1, max_samples=5)
    assert result.outcome is Outcome.SAMPLE_BUDGET and result.counts.samples == 5


def test_the_per_plan_sample_budget_moves_on_to_the_next_plan() -> None:
    result = sesame(nine_rooms().problem(), SesameBudgets(max_samples_per_plan=30), seed=0)
    assert result.solved
    first = result.attempts[0]
    assert first.outcome is Outcome.PLAN_SAMPLE_BUDGET
    assert sum(step.samples for step in first.steps) == 30


def test_the_plan_budget_counts_abstract_plans() -> None:
    problem = chain_problem(2, lambda action, _: action == "s1->s2", detour=True)
    result = sesame(problem, SesameBudgets(max_plans=1), seed=0)
    assert result.outcome is Outcome.PLAN_BUDGET and result.counts.abstract_plans == 1
    assert sesame(chain_problem(2, lambda action, _: action == "s1->s2", detour=True), seed=0).solved


def test_a_spent_time_budget_draws_no_sample() -> None:
    for result in (sesame(pillar_shadow().problem(), SesameBudgets(time_budget_s=0.0)),
                   abstract_bfs(pillar_shadow().problem(), time_budget_s=0.0)):
        assert result.outcome is Outcome.TIME_BUDGET and result.counts.samples == 0


def test_no_step_is_sampled_more_than_k_times_in_a_row_without_progress() -> None:
    k = 3
    events: list[SampleEvent[str, Passage]] = []
    backtracking_refinement(blocked_doorway().problem(), SesameBudgets(samples_per_step=k), seed=0,
                            on_sample=events.append)
    run = 0
    for before, event in zip([None, *events], events, strict=False):
        same_step = before is not None and before.step_index == event.step_index and not before.succeeded
        run = run + 1 if same_step else 1
        assert run <= k


def test_abstract_bfs_draws_at_most_n_samples_per_abstract_transition() -> None:
    result = abstract_bfs(walled_off().problem(), seed=0, samples_per_transition=4)
    assert result.graph.abstract_action_edges
    assert all(edge.samples <= 4 for edge in result.graph.abstract_action_edges)
