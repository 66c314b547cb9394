"""GBFS over alternating preferred/all queues: it escapes where helpful actions alone dead-end."""

from __future__ import annotations

from collections import deque
from pathlib import Path

import pytest

from kitchen_tamp.planning import Task, greedy_best_first_search, validate_plan
from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.search.alternating_greedy import AlternatingQueues
from tests.planning.conftest import data_task, written_task

GATE_DOMAIN = """(define (domain gate-trap)
  (:requirements :strips)
  (:predicates (at-start) (entry ?c) (in ?c) (adj ?a ?b) (button ?c) (exit ?c) (gate-open)
               (road-start ?r) (on-road ?r) (road-next ?a ?b) (road-end ?r) (done))
  (:action enter :parameters (?c) :precondition (and (at-start) (entry ?c))
    :effect (and (in ?c) (not (at-start))))
  (:action walk :parameters (?a ?b) :precondition (and (in ?a) (adj ?a ?b))
    :effect (and (in ?b) (not (in ?a)) (not (gate-open))))
  (:action press :parameters (?c) :precondition (and (in ?c) (button ?c)) :effect (gate-open))
  (:action leave :parameters (?c) :precondition (and (in ?c) (exit ?c) (gate-open)) :effect (done))
  (:action take-road :parameters (?r) :precondition (and (at-start) (road-start ?r))
    :effect (and (on-road ?r) (not (at-start))))
  (:action drive :parameters (?a ?b) :precondition (and (on-road ?a) (road-next ?a ?b))
    :effect (and (on-road ?b) (not (on-road ?a))))
  (:action arrive :parameters (?r) :precondition (and (on-road ?r) (road-end ?r)) :effect (done)))
"""


def gate_trap(tmp_path: Path, cells: int) -> Task:
    """A walled yard of ``cells`` cells in a row and a long road, both from the start.

    The yard's gate (at cell 0) opens from a button at the far end and closes
    whenever the robot walks, so the yard is a dead end; the relaxation ignores
    the closing and finds the yard shorter than the road, so entering the yard is
    the only helpful action at the start and every yard state has a finite h_FF.
    """
    road = cells + 4
    facts = ["(at-start)", "(entry c0)", "(exit c0)", f"(button c{cells - 1})", "(road-start r0)",
             f"(road-end r{road - 1})"]
    facts += [f"(adj c{i} c{i + 1}) (adj c{i + 1} c{i})" for i in range(cells - 1)]
    facts += [f"(road-next r{i} r{i + 1})" for i in range(road - 1)]
    objects = [f"c{i}" for i in range(cells)] + [f"r{i}" for i in range(road)]
    return written_task(tmp_path, GATE_DOMAIN, "gate-trap", f"gate-{cells}", objects, facts, "(done)")


def helpful_only_search_solves(task: Task) -> bool:
    """Breadth-first over helpful actions only (pyperplan's pruning): does it reach a goal?"""
    exploration = RelaxedExploration(task)
    seen = {task.initial_state}
    frontier = deque([task.initial_state])
    while frontier:
        state = frontier.popleft()
        if task.is_goal(state):
            return True
        h, helpful = exploration.h_ff_helpful(state)
        if h == INFINITY:
            continue
        for child, index in task.successor_indices(state):
            if (helpful >> index) & 1 and child not in seen:
                seen.add(child)
                frontier.append(child)
    return False


@pytest.mark.parametrize("lazy", [False, True])
@pytest.mark.parametrize("cells", [3, 12])
def test_gbfs_leaves_a_yard_that_helpful_actions_alone_never_leave(
        tmp_path: Path, cells: int, lazy: bool) -> None:
    task = gate_trap(tmp_path, cells)
    assert not helpful_only_search_solves(task)
    result = greedy_best_first_search(task, lazy=lazy)
    assert result.solved and result.plan is not None, result.message
    assert validate_plan(task, result.plan).valid
    assert result.plan[0].name == "take-road" and len(result.plan) == cells + 5


@pytest.mark.parametrize("lazy", [False, True])
def test_gbfs_escapes_the_helpful_trap(lazy: bool) -> None:
    task = data_task("helpful_trap_problem.pddl", "helpful_trap_domain.pddl")
    assert not helpful_only_search_solves(task)
    result = greedy_best_first_search(task, lazy=lazy)
    assert [str(a) for a in result.plan or ()] == ["prepare", "finish-prepared"]


@pytest.mark.parametrize("lazy", [False, True])
def test_eager_and_lazy_gbfs_are_complete_and_deterministic(small_task: Task, lazy: bool) -> None:
    first = greedy_best_first_search(small_task, lazy=lazy)
    assert first.solved and first.plan is not None and validate_plan(small_task, first.plan).valid
    assert greedy_best_first_search(small_task, lazy=lazy).plan == first.plan
    unsolvable = data_task("delivery_unsolvable.pddl", "delivery_domain.pddl")
    assert greedy_best_first_search(unsolvable, lazy=lazy).status == "unsolvable"


def test_queues_take_turns_and_a_boost_gives_the_preferred_queue_a_run() -> None:
    queues: AlternatingQueues[str] = AlternatingQueues(boost=3)
    for name in "abcdef":
        queues.push((1.0,), name, preferred=name in "def")
    # Turns: all-queue first on a tie, then preferred, ...; each queue first-in first-out.
    assert [queues.pop() for _ in range(4)] == ["a", "d", "b", "e"]
    queues.boost()  # the preferred queue now has 3 turns in hand
    assert [queues.pop() for _ in range(2)] == ["f", "c"]  # preferred runs dry: the all-queue goes on
    assert [queues.pop() for _ in range(3)] == ["d", "e", "f"]  # preferred entries also sit in the all-queue
    assert not queues
