"""One seed, one plan; another seed, other samples."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from kitchen_tamp.bilevel import (
    BilevelProblem,
    BilevelResult,
    SesameBudgets,
    abstract_bfs,
    backtracking_refinement,
    greedy_refinement,
    sesame,
)
from kitchen_tamp.bilevel.toy_rooms import Passage, Point, nine_rooms

RoomsProblem = BilevelProblem[Point, Point, str, Passage]
Planner = Callable[[RoomsProblem, int], BilevelResult[Point, Point, str, Passage]]

PLANNERS: dict[str, Planner] = {
    "abstract_bfs": lambda problem, seed: abstract_bfs(problem, seed=seed),
    "greedy": lambda problem, seed: greedy_refinement(problem, seed=seed),
    "backtracking": lambda problem, seed: backtracking_refinement(
        problem, SesameBudgets(max_samples=300), seed=seed),
    "sesame": lambda problem, seed: sesame(problem, SesameBudgets(max_samples_per_plan=60), seed=seed),
}


def fingerprint(result: BilevelResult[Point, Point, str, Passage]) -> tuple[object, ...]:
    states = () if result.plan is None else tuple(
        tuple(np.round(state, 12)) for state in result.plan.trajectory.states)
    return (result.outcome, result.counts, len(result.graph.state_nodes), states,
            tuple(failed.message for failed in result.graph.failed_samples))


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_the_same_seed_gives_the_same_plan(name: str) -> None:
    planner = PLANNERS[name]
    problem = nine_rooms().problem()
    for seed in (1, 2):
        assert fingerprint(planner(problem, seed)) == fingerprint(planner(problem, seed))


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_other_seeds_sample_elsewhere(name: str) -> None:
    planner = PLANNERS[name]
    problem = nine_rooms().problem()
    assert len({fingerprint(planner(problem, seed)) for seed in range(4)}) > 1
