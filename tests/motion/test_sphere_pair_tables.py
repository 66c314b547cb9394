"""Pair tables (`sphere_pair_tables`): every settled cell is right at its worst points (the corners,
farthest from the centre it was proved at), and the kernel's verdicts with the tables are the
kernel's verdicts without them."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene, sample_targets
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.layout import kernel_arguments
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_configurations
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import validity_arrays
from kitchen_tamp.motion.geometry.spheres.pair_tables import PairTables, pair_tables
from kitchen_tamp.world.scene_description import describe_collision_checker

KERNEL: Any = valid_configurations
CORNERS_PER_STATE = 3000


@pytest.fixture(scope="module")
def checkers(kitchen: KitchenScene) -> list[SphereCollisionChecker]:
    """The free hand, and the hand holding spam as the pick skill grasped it."""
    built = [SphereCollisionChecker(describe_collision_checker(kitchen.collision_checker()))]
    with kitchen.scene.preserved():
        sample_targets(kitchen, "pickUp", ("spam", "countertop"), np.random.default_rng(0)).apply(kitchen)
        assert kitchen.held_box() == "spam"
        built.append(SphereCollisionChecker(describe_collision_checker(kitchen.collision_checker())))
    return built


def tables_of(checker: SphereCollisionChecker) -> tuple[tuple[Any, ...], PairTables]:
    plain = kernel_arguments(checker.model, checker.lower, checker.upper)
    return plain, pair_tables(checker.model, plain, checker.margin)


def test_link5_and_link7_have_a_table_that_settles_most_cells(checkers: list[SphereCollisionChecker]) -> None:
    model = checkers[0].model
    _, tables = tables_of(checkers[0])
    names = [(model.groups[g].link, model.groups[h].link) for g, h in model.group_pairs.tolist()]
    k = names.index(("panda_link5", "panda_link7"))
    t = int(tables.pair_tables[k])
    assert t >= 0 and tables.variables[t].tolist() == [5, 6]
    cells = tables.cells[tables.offsets[t] : tables.offsets[t] + int(np.prod(tables.counts[t]))]
    assert np.mean(cells != 0) > 0.9
    assert np.any(cells < 0) and np.any(cells > 0)


def test_settled_cells_hold_at_their_corners(checkers: list[SphereCollisionChecker]) -> None:
    rng = np.random.default_rng(21)
    for checker in checkers:
        plain, tables = tables_of(checker)
        *shared, _, _ = plain
        for k, (g, h) in enumerate(checker.model.group_pairs.tolist()):
            t = int(tables.pair_tables[k])
            if t < 0:
                continue
            counts = tables.counts[t]
            cells = tables.cells[tables.offsets[t] : tables.offsets[t] + int(np.prod(counts))]
            pair = np.array([[g, h, -1]], dtype=np.int64)
            for state in (1, -1):
                settled = np.flatnonzero(cells == state)
                if len(settled) == 0:
                    continue
                chosen = rng.choice(settled, size=min(CORNERS_PER_STATE, len(settled)))
                cell = np.stack([chosen // counts[1], chosen % counts[1]], axis=1)
                corner = cell + rng.integers(0, 2, size=cell.shape) * (1.0 - 1e-9)
                qs = rng.uniform(checker.lower, checker.upper, size=(len(chosen), 7))
                qs[:, tables.variables[t]] = tables.lows[t] + corner * tables.steps[t]
                alone_arrays = validity_arrays((*shared, np.zeros((0, 2), dtype=np.int64), pair))
                alone = KERNEL(qs, alone_arrays, checker.margin, False)
                assert np.all(alone == (state > 0)), (checker.model.groups[h].name, state)


def test_tables_change_no_verdict(checkers: list[SphereCollisionChecker]) -> None:
    rng = np.random.default_rng(22)
    for checker in checkers:
        plain, _ = tables_of(checker)
        qs = rng.uniform(checker.lower - 0.02, checker.upper + 0.02, size=(20000, 7))
        for margin in (checker.margin, checker.margin + 0.002, checker.margin - 0.002):
            with_tables = checker.with_margin(margin).is_valid(qs)
            without = KERNEL(qs, validity_arrays(plain), margin, False)
            assert with_tables.tolist() == without.tolist()
        untabled = copy.copy(checker)
        untabled._kernel_arguments = plain
        untabled._unpadded = untabled._unpadded_passes()
        assert checker.is_valid_without_padding(qs).tolist() == untabled.is_valid_without_padding(qs).tolist()
