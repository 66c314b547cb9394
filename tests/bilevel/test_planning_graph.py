"""The planning graph record is consistent with the counts and with the plan, for every planner."""

from __future__ import annotations

import pytest

from kitchen_tamp.bilevel import SampleEvent, SesameBudgets, abstract_bfs, sesame
from kitchen_tamp.bilevel.toy_rooms import Passage, nine_rooms


@pytest.mark.parametrize("planner", ["abstract_bfs", "sesame"])
def test_graph_record_matches_counts_and_plan(planner: str) -> None:
    problem = nine_rooms().problem()
    events: list[SampleEvent[str, Passage]] = []
    if planner == "sesame":
        result = sesame(problem, SesameBudgets(max_samples_per_plan=60), seed=1, on_sample=events.append)
    else:
        result = abstract_bfs(problem, seed=1, on_sample=events.append)
    graph, counts = result.graph, result.counts
    assert result.solved and result.plan is not None

    # every state node has exactly one abstractor edge, to the abstract state of its state
    assert [edge.state_node for edge in graph.abstractor_edges] == [node.id for node in graph.state_nodes]
    psi = problem.abstraction.abstract_state
    assert all(psi(graph.state(edge.state_node)) == edge.abstract_state for edge in graph.abstractor_edges)
    assert set(graph.abstract_states) == {edge.abstract_state for edge in graph.abstractor_edges}

    # one action edge per successful sample, one failed sample per failure
    assert len(graph.action_edges) == len(graph.state_nodes) - 1 == counts.samples - counts.failures
    assert len(graph.failed_samples) == counts.failures
    assert sum(edge.samples for edge in graph.abstract_action_edges) == counts.samples
    assert sum(edge.failures for edge in graph.abstract_action_edges) == counts.failures

    # the callback saw every sample, in order
    assert [event.sample for event in events] == list(range(1, counts.samples + 1))
    assert sum(not event.succeeded for event in events) == counts.failures
    assert all((event.failure is None) == event.succeeded for event in events)

    # the plan is a path of action edges from the initial state node
    last = events[-1].target_node
    assert last is not None
    path = graph.path_to(last)
    assert [edge.transition for edge in path] == [step.transition for step in result.plan.steps]
    assert path[0].source == 0


def test_sesame_events_name_plan_and_step() -> None:
    events: list[SampleEvent[str, Passage]] = []
    result = sesame(nine_rooms().problem(), SesameBudgets(max_samples_per_plan=20), seed=0,
                    on_sample=events.append)
    assert result.counts.abstract_plans > 1
    assert {event.plan_index for event in events} == set(range(result.counts.abstract_plans))
    assert all(event.step_index is not None for event in events)
    first_plan = [event for event in events if event.plan_index == 0]
    assert first_plan[0].step_index == 0 and first_plan[0].source_node == 0
