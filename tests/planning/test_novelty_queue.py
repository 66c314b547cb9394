"""The novel queue of GBFS: it leaves a dead-end plateau that the relaxation cannot see."""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import Task, greedy_best_first_search, validate_plan
from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.search.alternating_greedy import (
    AlternatingQueues,
    Novelty,
    alternating_greedy_search,
)
from kitchen_tamp.planning.search.result import SearchBudget
from tests.planning.conftest import written_task

PLATEAU_DOMAIN = """(define (domain switch-plateau)
  (:requirements :strips)
  (:predicates (at-start) (in-room) (token) (half-a) (half-b) (off ?s) (on ?s)
               (on-road ?r) (road-next ?a ?b) (road-start ?r) (road-end ?r) (done))
  (:action enter-room :parameters () :precondition (at-start)
    :effect (and (in-room) (not (at-start))))
  (:action flip-on :parameters (?s) :precondition (and (in-room) (off ?s))
    :effect (and (on ?s) (not (off ?s))))
  (:action flip-off :parameters (?s) :precondition (and (in-room) (on ?s))
    :effect (and (off ?s) (not (on ?s))))
  (:action make-a :parameters () :precondition (and (in-room) (token))
    :effect (and (half-a) (not (token))))
  (:action make-b :parameters () :precondition (and (in-room) (token))
    :effect (and (half-b) (not (token))))
  (:action join :parameters () :precondition (and (half-a) (half-b)) :effect (done))
  (:action take-road :parameters (?r) :precondition (and (at-start) (road-start ?r))
    :effect (and (on-road ?r) (not (at-start))))
  (:action drive :parameters (?a ?b) :precondition (and (on-road ?a) (road-next ?a ?b))
    :effect (and (on-road ?b) (not (on-road ?a))))
  (:action arrive :parameters (?r) :precondition (and (on-road ?r) (road-end ?r)) :effect (done)))
"""


def switch_plateau(tmp_path: Path, switches: int, road: int = 6) -> Task:
    """A room that looks three steps from the goal and a road that looks ``road`` + 1 steps away.

    In the room, both halves of the goal need the one token, so the room is a
    dead end; but the relaxation reuses the token, so every room state has
    h_FF = 3, below every state on the road. ``switches`` light switches in the
    room change nothing the goal needs, so the room is a plateau of
    2^``switches`` states at h = 3 that a search ordered by h empties before
    it tries the road.
    """
    facts = ["(at-start)", "(token)", "(road-start r0)", f"(road-end r{road - 1})"]
    facts += [f"(off s{i})" for i in range(switches)]
    facts += [f"(road-next r{i} r{i + 1})" for i in range(road - 1)]
    objects = [f"s{i}" for i in range(switches)] + [f"r{i}" for i in range(road)]
    return written_task(tmp_path, PLATEAU_DOMAIN, "switch-plateau", f"plateau-{switches}", objects, facts,
                        "(done)")


def test_the_room_is_an_unseen_dead_end_below_the_road(tmp_path: Path) -> None:
    task = switch_plateau(tmp_path, switches=3)
    exploration = RelaxedExploration(task, "hadd")
    room = next(a for a in task.actions if a.name == "enter-room").apply(task.initial_state)
    road = next(a for a in task.actions if a.name == "take-road").apply(task.initial_state)
    assert exploration.h_ff(room) == 3 < exploration.h_ff(road) < INFINITY
    for action in task.actions:
        if action.name.startswith("make-"):
            assert exploration.h_ff(action.apply(room)) == INFINITY  # the token is gone


@pytest.mark.parametrize("lazy", [True, False])
def test_the_novel_queue_takes_the_road_long_before_the_plateau_is_exhausted(
        tmp_path: Path, lazy: bool) -> None:
    switches = 12  # 4096 room states
    task = switch_plateau(tmp_path, switches)
    budget = 200
    with_novelty = greedy_best_first_search(task, lazy=lazy, max_expansions=budget)
    assert with_novelty.solved and with_novelty.plan is not None, with_novelty.message
    assert validate_plan(task, with_novelty.plan).valid
    assert [a.name for a in with_novelty.plan] == ["take-road", *["drive"] * 5, "arrive"]
    without = alternating_greedy_search(task, SearchBudget(None, budget), lazy=lazy, novelty=False,
                                      landmarks=False)
    assert without.status == "budget"  # still flipping switches in the room
    complete = alternating_greedy_search(task, SearchBudget(None, None), lazy=lazy, novelty=False,
                                      landmarks=False)
    assert complete.solved and complete.expanded > 2 ** switches


def test_a_state_is_novel_when_it_holds_an_atom_no_earlier_state_held() -> None:
    novelty = Novelty(enabled=True)
    assert novelty.is_novel(0b0011)
    assert not novelty.is_novel(0b0001)  # a subset of what was seen
    assert novelty.is_novel(0b0101)
    assert not novelty.is_novel(0b0111)
    assert not Novelty(enabled=False).is_novel(0b1000)


def test_the_novel_queue_takes_its_turn_and_shares_the_boost() -> None:
    queues: AlternatingQueues[str] = AlternatingQueues(boost=2)
    for name, preferred, novel in [("a", False, False), ("b", True, False), ("c", False, True),
                                   ("d", False, False), ("e", True, True)]:
        queues.push((1.0,), name, preferred, novel)
    # Turns in the order all, preferred, novel; each queue first-in first-out.
    assert [queues.pop() for _ in range(3)] == ["a", "b", "c"]
    queues.boost()  # preferred and novel now have 2 turns in hand each: they alternate
    assert [queues.pop() for _ in range(2)] == ["e", "e"]
    assert [queues.pop() for _ in range(4)] == ["b", "c", "d", "e"]  # only the all-queue is left
    assert not queues
