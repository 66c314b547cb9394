from __future__ import annotations

import itertools
from collections.abc import Iterator

import numpy as np

from kitchen_tamp.bilevel import AbstractPlan, shortest_first_plans

Cell = tuple[int, int]
SIZE = 3
MOVES = (("up", (-1, 0)), ("down", (1, 0)), ("left", (0, -1)), ("right", (0, 1)))


def grid_successors(cell: Cell) -> Iterator[tuple[str, Cell]]:
    """A SIZE x SIZE grid of abstract states with moves in four directions."""
    r, c = cell
    for name, (dr, dc) in MOVES:
        if 0 <= r + dr < SIZE and 0 <= c + dc < SIZE:
            yield name, (r + dr, c + dc)


def in_far_corner(cell: Cell) -> bool:
    return cell == (SIZE - 1, SIZE - 1)


def plans(seed: int, count: int, *, max_length: int | None = None,
          max_abstract_states: int = 1000) -> list[AbstractPlan[Cell, str]]:
    generate = shortest_first_plans(grid_successors, in_far_corner, max_length=max_length,
                                    max_abstract_states=max_abstract_states)
    return list(itertools.islice(generate((0, 0), np.random.default_rng(seed)), count))


def is_valid(plan: AbstractPlan[Cell, str]) -> bool:
    chained = all((t.action, t.target) in list(grid_successors(t.source)) for t in plan.transitions)
    return chained and in_far_corner(plan.states[-1]) and len(set(plan.states)) == len(plan.states)


def test_plans_come_shortest_first_distinct_acyclic_and_valid() -> None:
    found = plans(0, 30)
    lengths = [len(plan) for plan in found]
    assert lengths[0] == 4 and lengths == sorted(lengths)
    assert sum(length == 4 for length in lengths) == 6  # C(4, 2) monotone paths
    assert len({plan.actions for plan in found}) == len(found)
    assert all(is_valid(plan) for plan in found)


def test_the_seed_orders_equally_short_plans() -> None:
    assert [p.actions for p in plans(3, 6)] == [p.actions for p in plans(3, 6)]
    orders = {tuple(p.actions for p in plans(seed, 6)) for seed in range(8)}
    assert len(orders) > 1


def test_max_length_bounds_the_enumeration() -> None:
    found = plans(0, 1000, max_length=4)
    assert len(found) == 6 and all(len(plan) == 4 for plan in found)


def test_without_goal_distances_the_search_is_still_shortest_first() -> None:
    found = plans(0, 30, max_abstract_states=2)
    lengths = [len(plan) for plan in found]
    assert lengths[0] == 4 and lengths == sorted(lengths)
    assert all(is_valid(plan) for plan in found)


def test_an_unreachable_goal_gives_no_plan_and_a_goal_start_the_empty_plan() -> None:
    def successors(state: str) -> Iterator[tuple[str, str]]:
        yield from {"a": [("ab", "b")], "b": [("ba", "a")]}.get(state, [])

    rng = np.random.default_rng(0)
    assert list(shortest_first_plans(successors, lambda s: s == "z")("a", rng)) == []
    assert list(shortest_first_plans(successors, lambda s: s == "a")("a", rng)) == [AbstractPlan(("a",), ())]
