from __future__ import annotations

import itertools
import random

import numpy as np

from kitchen_tamp.planning import Task, iter_plans, plan, validate_plan


def test_plans_come_shortest_first_valid_and_distinct(small_task: Task) -> None:
    plans = list(itertools.islice(iter_plans(small_task), 25))
    assert plans
    lengths = [len(p) for p in plans]
    assert lengths == sorted(lengths)
    assert lengths[0] == len(plan(small_task, "bfs").plan or ())
    assert len(set(plans)) == len(plans)
    for candidate in plans:
        assert validate_plan(small_task, candidate).valid


def test_seeded_tie_breaking_is_reproducible(small_task: Task) -> None:
    def first(seed: int) -> list[tuple[str, ...]]:
        plans = itertools.islice(iter_plans(small_task, rng=np.random.default_rng(seed)), 6)
        return [tuple(str(a) for a in p) for p in plans]

    assert first(7) == first(7)


def test_a_stdlib_random_source_breaks_ties_as_reproducibly(small_task: Task) -> None:
    def first(seed: int) -> list[tuple[str, ...]]:
        plans = itertools.islice(iter_plans(small_task, rng=random.Random(seed)), 6)
        return [tuple(str(a) for a in p) for p in plans]

    assert first(3) == first(3)
    lengths = [len(p) for p in first(3)]
    assert lengths == sorted(lengths)


def test_max_length_bounds_the_enumeration(small_task: Task) -> None:
    optimum = len(plan(small_task, "bfs").plan or ())
    plans = list(iter_plans(small_task, max_length=optimum))
    assert plans and all(len(p) == optimum for p in plans)
