from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from kitchen_tamp.planning import RelaxedExploration, Task
from kitchen_tamp.planning.heuristics import INFINITY
from tests.planning.brute_force import goal_distances, reachable_states
from tests.planning.conftest import data_task

if TYPE_CHECKING:
    from kitchen_tamp.planning.heuristics import RelaxedPlanSupporters


def test_h_max_is_admissible_and_below_h_add(small_task: Task) -> None:
    exploration = RelaxedExploration(small_task)
    distances = goal_distances(small_task)
    for state in reachable_states(small_task):
        h_max = exploration.h_max(state)
        if state in distances:
            assert h_max <= distances[state]
        assert h_max <= exploration.h_add(state)


def test_heuristics_are_zero_exactly_at_goals_and_infinite_only_at_dead_ends(
        small_task: Task) -> None:
    exploration = RelaxedExploration(small_task)
    distances = goal_distances(small_task)
    for state in reachable_states(small_task):
        h_ff = exploration.h_ff(state)
        if small_task.is_goal(state):
            assert h_ff == 0
        elif small_task.negative_goal_atoms == frozenset():
            assert h_ff > 0
        if h_ff == INFINITY:
            assert state not in distances  # never prunes a state that has a plan


@pytest.mark.parametrize("supporters", ["ff", "hadd"])
def test_relaxed_plan_reaches_the_goal_when_deletes_are_ignored(
        small_task: Task, supporters: RelaxedPlanSupporters) -> None:
    exploration = RelaxedExploration(small_task, supporters)
    for start in reachable_states(small_task):
        relaxed = exploration.relaxed_plan(start)
        if relaxed is None:
            assert exploration.h_max(start) == INFINITY
            continue
        assert len(relaxed) == len(set(relaxed)) >= exploration.h_max(start)
        assert reaches_goal_relaxed(small_task, start, relaxed)


def reaches_goal_relaxed(small_task: Task, state: int, relaxed: list[int]) -> bool:
    remaining = set(relaxed)
    while remaining:  # apply in any executable order, ignoring deletes
        ready = [i for i in sorted(remaining) if state & small_task.actions[i].pre
                 == small_task.actions[i].pre]
        if not ready:
            return False  # not executable under the delete relaxation
        for i in ready:
            state |= small_task.actions[i].add
            remaining.discard(i)
    return state & small_task.goal == small_task.goal


def test_relaxed_plan_takes_the_achiever_with_the_lowest_difficulty() -> None:
    task = data_task("achiever_problem.pddl", "achiever_domain.pddl")
    exploration = RelaxedExploration(task)
    relaxed = exploration.relaxed_plan(task.initial_state)
    assert relaxed is not None
    assert sorted(str(task.actions[i]) for i in relaxed) == ["easy-way", "make-c"]
    assert exploration.h_ff(task.initial_state) == 2


def test_helpful_actions_are_the_applicable_actions_of_the_relaxed_plan(small_task: Task) -> None:
    exploration = RelaxedExploration(small_task)
    for state in reachable_states(small_task):
        h, helpful = exploration.h_ff_helpful(state)
        assert h == exploration.h_ff(state)
        relaxed = set(exploration.relaxed_plan(state) or ())
        chosen = {i for i in range(len(small_task.actions)) if helpful >> i & 1}
        assert chosen == {i for i in relaxed if small_task.actions[i].pre & state
                          == small_task.actions[i].pre}
        # A relaxed plan can always start somewhere, so only goals and dead ends have none.
        assert bool(chosen) == (0 < h < INFINITY)


def test_helpful_actions_can_lead_into_a_dead_end() -> None:
    task = data_task("helpful_trap_problem.pddl", "helpful_trap_domain.pddl")
    exploration = RelaxedExploration(task)
    _, helpful = exploration.h_ff_helpful(task.initial_state)
    assert [str(a) for i, a in enumerate(task.actions) if helpful >> i & 1] == ["commit"]
    committed = next(a for a in task.actions if a.name == "commit").apply(task.initial_state)
    assert exploration.h_ff(committed) == INFINITY


def reference_h_add(task: Task, state: int) -> list[float]:
    """h_add of every atom by fixpoint iteration: 0 in ``state``, else min over achievers of 1 + sum."""
    cost = [0.0 if state >> atom & 1 else INFINITY for atom in range(len(task.atoms))]
    changed = True
    while changed:
        changed = False
        for action in task.actions:
            offer = 1 + sum(cost[p] for p in action.pre_ids)
            for atom in action.add_ids:
                if offer < cost[atom]:
                    cost[atom], changed = offer, True
    return cost


def test_additive_costs_and_supporters_match_a_fixpoint_reference(small_task: Task) -> None:
    exploration = RelaxedExploration(small_task, "hadd")
    for state in reachable_states(small_task):
        reference = reference_h_add(small_task, state)
        goal_costs = [reference[g] for g in exploration.goal_ids]
        explored = exploration.additive_costs(state)
        if INFINITY in goal_costs:
            assert explored is None
            continue
        assert explored is not None
        cost, supporter = explored
        assert exploration.h_add(state) == sum(goal_costs)
        # Every atom it settled (only relevant actions take part) cheaper than the dearest
        # goal atom has its h_add cost, and its supporter achieves it at exactly that cost.
        for atom, expected in enumerate(reference):
            if cost[atom] < INFINITY and expected < max(goal_costs, default=0.0):
                assert cost[atom] == expected
                if expected > 0:
                    action = small_task.actions[supporter[atom]]
                    assert atom in action.add_ids
                    assert 1 + sum(reference[p] for p in action.pre_ids) == expected


def test_additive_costs_repeat_with_a_larger_weight_when_costs_come_near_it(small_task: Task) -> None:
    exploration = RelaxedExploration(small_task, "hadd")
    for state in reachable_states(small_task):
        # A weight of 2 is below most sums of costs: the exploration must notice and redo.
        assert exploration.additive_costs(state, unsettled=2) == exploration.additive_costs(state)
