"""Abstract BFS grows its graph breadth-first and keeps several low-level states per abstract state."""

from __future__ import annotations

from collections import deque

from kitchen_tamp.bilevel import Outcome, abstract_bfs, backtracking_refinement
from kitchen_tamp.bilevel.toy_rooms import RoomsWorld, blocked_doorway, nine_rooms, pillar_shadow, walled_off
from tests.bilevel.valid_plans import assert_valid_toy_plan


def door_distances(world: RoomsWorld, start: str) -> dict[str, int]:
    distance = {start: 0}
    frontier = deque([start])
    while frontier:
        room = frontier.popleft()
        for door in world.doors_of(room):
            if door.other_room(room) not in distance:
                distance[door.other_room(room)] = distance[room] + 1
                frontier.append(door.other_room(room))
    return distance


def test_abstract_bfs_finds_a_plan_around_the_blocked_doorway() -> None:
    scene = blocked_doorway()
    problem = scene.problem()
    result = abstract_bfs(problem, seed=0)
    assert result.solved and result.counts.abstract_plans == 0 and result.attempts == ()
    assert result.plan is not None
    assert [step.transition.target for step in result.plan.steps] == ["D", "E", "F", "C"]
    assert_valid_toy_plan(scene, problem, result.plan)
    blocked = [e for e in result.graph.abstract_action_edges if e.transition.action.door == "B-C"]
    assert blocked and all(edge.failures == edge.samples for edge in blocked)


def test_abstract_states_are_sampled_in_breadth_first_order() -> None:
    scene = nine_rooms()
    result = abstract_bfs(scene.problem(), seed=1)
    assert result.solved
    depth = door_distances(scene.world, "G")
    sources = [depth[edge.transition.source] for edge in result.graph.abstract_action_edges]
    assert sources == sorted(sources)
    # no transition back into an abstract state that was already expanded
    edges = result.graph.abstract_action_edges
    assert all(depth[edge.transition.target] >= depth[edge.transition.source] for edge in edges)


def test_several_low_level_states_per_abstract_state_get_around_a_bad_sample() -> None:
    scene = pillar_shadow()
    problem = scene.problem()
    result = abstract_bfs(problem, seed=0, samples_per_transition=5)
    assert result.solved
    in_b = result.graph.nodes_in("B")
    assert len(in_b) >= 2
    assert_valid_toy_plan(scene, problem, result.plan)


def test_abstract_bfs_fails_when_every_sample_into_the_shadow_is_bad() -> None:
    # seed 1: all three samples into B land where door B-C is hidden (backtracking samples on and succeeds)
    problem = pillar_shadow().problem()
    result = abstract_bfs(problem, seed=1)
    assert result.outcome is Outcome.GRAPH_EXHAUSTED
    assert len(result.graph.nodes_in("B")) == 3 and result.graph.nodes_in("C") == []
    assert backtracking_refinement(problem, seed=1).solved


def test_abstract_bfs_explores_everything_reachable_before_giving_up() -> None:
    result = abstract_bfs(walled_off().problem(), seed=0)
    assert result.outcome is Outcome.GRAPH_EXHAUSTED
    assert set(result.graph.abstract_states) == {"A", "B"}
