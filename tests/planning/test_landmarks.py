"""Landmarks and their orderings hold on every plan; the landmark count guides GBFS and never prunes."""

from __future__ import annotations

from itertools import islice

from kitchen_tamp.planning import GroundAction, Task, iter_plans
from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.landmarks import landmark_graph
from kitchen_tamp.planning.task import bits
from tests.planning.brute_force import goal_distances, reachable_states
from tests.planning.conftest import data_task


def _plan_states(task: Task, plan: tuple[GroundAction, ...]) -> list[int]:
    states = [task.initial_state]
    for action in plan:
        states.append(action.apply(states[-1]))
    return states


def test_every_landmark_and_ordering_holds_on_the_shortest_plans(small_task: Task) -> None:
    graph = landmark_graph(RelaxedExploration(small_task), small_task.initial_state)
    assert graph is not None
    assert small_task.goal & ~graph.landmarks == 0  # goal atoms are landmarks
    for plan in islice(iter_plans(small_task), 50):
        states = _plan_states(small_task, plan)
        first = {atom: next(i for i, state in enumerate(states) if state >> atom & 1)
                 for atom in bits(graph.landmarks)}
        for atom in bits(graph.landmarks):
            for before in bits(graph.natural[atom]):
                assert first[before] < first[atom]  # held at some time before the landmark first does
            for before in bits(graph.greedy_necessary[atom]):
                assert states[first[atom] - 1] >> before & 1  # held right before it


def test_sussman_has_the_landmarks_every_plan_needs() -> None:
    task = data_task("blocks_sussman.pddl", "blocks_domain.pddl")
    graph = landmark_graph(RelaxedExploration(task), task.initial_state)
    assert graph is not None
    names = {" ".join(task.atoms[atom]) for atom in bits(graph.landmarks & ~task.initial_state)}
    # A and B must be held to be stacked, and A cleared (C taken off it) before A is picked up.
    assert {"on a b", "on b c", "holding a", "holding b", "clear a"} <= names


def test_the_landmark_count_is_zero_at_goals_reached_in_order_and_never_prunes_a_state_with_a_plan(
        small_task: Task) -> None:
    evaluator = LandmarkEvaluator(RelaxedExploration(small_task, "hadd"))
    distances = goal_distances(small_task)
    for plan in islice(iter_plans(small_task), 10):
        evaluation = evaluator.root()
        for state in _plan_states(small_task, plan)[1:]:
            evaluation = evaluator.child(state, evaluation.accepted)
        assert evaluation.h_landmarks == 0  # a plan reaches every landmark after those ordered before it
    for state in reachable_states(small_task):
        if evaluator.evaluate(state, 0).h_ff == INFINITY:
            assert state not in distances
