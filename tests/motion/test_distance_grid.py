"""The obstacles' distance grid of the validity kernel: never closer to the truth than an obstacle
is, and the kernel's verdicts with it are the verdicts without it."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.motion.geometry.primitive_scene import PrimitiveObstacle, arm_among_obstacles
from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.ahead_of_time import valid_configurations_of_fields
from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid import distance_grid_cells, grid_clearance
from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid_frame import GRID_REACH, grid_frame
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import box_gap_at
from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import (
    ALL_FIELDS,
    VALIDITY_FIELDS,
    with_derived,
)
from kitchen_tamp.motion.motion_bench_maker import mbm_panda
from kitchen_tamp.world import panda_urdf_path
from tests.motion.poses import pose

CELLS: Any = distance_grid_cells
CLEARANCE: Any = grid_clearance
GAP: Any = box_gap_at
VALID: Any = valid_configurations_of_fields
"""The compiled kernels, untyped for mypy (numba's dispatcher stubs take no argument list)."""


OBSTACLES = (
    PrimitiveObstacle("table", "box", np.array([0.5, 0.8, 0.03]), pose((0.55, 0.0, 0.2), (0.0, 0.0, 0.3))),
    PrimitiveObstacle(
        "tilted board", "box", np.array([0.2, 0.02, 0.3]), pose((0.3, 0.4, 0.55), (0.5, 0.2, 0.9))
    ),
    PrimitiveObstacle("can", "cylinder", np.array([0.04, 0.25]), pose((0.45, -0.3, 0.35), (1.1, 0.0, 0.4))),
    PrimitiveObstacle("ball", "sphere", np.array([0.08]), pose((0.2, -0.5, 0.7), (0.0, 0.0, 0.0))),
)


@pytest.fixture(scope="module")
def spheres(tmp_path_factory: pytest.TempPathFactory) -> Iterator[SphereCollisionChecker]:
    scene = arm_among_obstacles(mbm_panda(panda_urdf_path(), ()), OBSTACLES, tmp_path_factory.mktemp("urdf"))
    yield SphereCollisionChecker(scene)


def _boxes(checker: SphereCollisionChecker) -> dict[str, Any]:
    return dict(zip(VALIDITY_FIELDS, checker.kernel_arguments, strict=True))


def test_no_point_is_read_farther_from_the_obstacles_than_it_is(spheres: SphereCollisionChecker) -> None:
    boxes = _boxes(spheres)
    frame, shape = grid_frame(boxes["box_lows"], boxes["box_highs"])
    shapes = (boxes["box_rotations"], boxes["box_centers"], boxes["box_halves"], boxes["box_kinds"])
    cells = CELLS(frame, shape, *shapes, boxes["box_lows"], boxes["box_highs"])
    low, high = frame[:3], frame[:3] + frame[3] * shape
    rng = np.random.default_rng(4)
    points = rng.uniform(low - 0.4, high + 0.4, size=(20_000, 3))
    read = np.array([CLEARANCE(*(point - low), 1.0 / frame[3], frame[4], shape, cells) for point in points])
    nearest = np.array(
        [min(GAP(*point, *shapes, b) for b in range(len(OBSTACLES))) for point in points]
    )
    assert np.all(read <= np.maximum(nearest, 0.0))  # a point inside an obstacle reads 0
    assert np.any(nearest < 0.0) and np.mean(read >= 0.1) > 0.3  # points inside, and many far out
    assert read.max() == pytest.approx(GRID_REACH)
    inside = np.all((points >= low) & (points < high), axis=1)
    # Within a byte's step and a cell's diagonal of the truth (the centre's distance, less half the
    # diagonal, read at a point up to half the diagonal from the centre), below the cap.
    near = inside & (nearest < GRID_REACH - frame[3])
    assert np.all(nearest[near] - read[near] <= frame[3] * np.sqrt(3) + GRID_REACH / 255 + 1e-12)


def test_a_scene_without_obstacles_has_a_grid_that_clears_nothing() -> None:
    frame, shape = grid_frame(np.zeros((0, 3)), np.zeros((0, 3)))
    assert shape.tolist() == [0, 0, 0]
    no_boxes = (np.zeros((0, 3, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0, np.int64))
    no_boxes += (np.zeros((0, 3)), np.zeros((0, 3)))
    cells = CELLS(frame, shape, *no_boxes)
    assert cells.size == 0
    assert CLEARANCE(0.1, 0.2, 0.3, 1.0 / frame[3], frame[4], shape, cells) == 0.0


def test_a_large_scene_gets_larger_cells_not_more() -> None:
    frame, shape = grid_frame(np.array([[-5.0, -5.0, 0.0]]), np.array([[5.0, 5.0, 3.0]]))
    assert int(np.prod(shape)) <= 1 << 18
    assert np.all(frame[:3] + frame[3] * shape >= np.array([5.3, 5.3, 3.3]))


def test_the_kernel_gives_the_verdicts_it_gives_without_the_grid(spheres: SphereCollisionChecker) -> None:
    fields = list(with_derived(spheres.kernel_arguments, distance_grid_cells))
    without = list(fields)
    without[ALL_FIELDS.index("grid_frame")] = np.array([0.0, 0.0, 0.0, 1.0, 0.0])  # a grid of no cells
    without[ALL_FIELDS.index("grid_shape")] = np.zeros(3, dtype=np.int64)
    without[ALL_FIELDS.index("grid_cells")] = np.zeros(0, dtype=np.uint8)
    rng = np.random.default_rng(9)
    qs = rng.uniform(spheres.lower, spheres.upper, size=(6000, 7))
    with_grid = VALID(tuple(fields), qs, spheres.margin, False)
    assert np.array_equal(with_grid, VALID(tuple(without), qs, spheres.margin, False))
    assert 0.2 < with_grid.mean() < 0.95  # the obstacles are in the arm's way
    assert np.array_equal(with_grid, spheres.is_valid(qs))


def test_models_of_the_same_obstacles_share_one_grid_and_others_get_their_own(
    spheres: SphereCollisionChecker,
) -> None:
    arguments = spheres.kernel_arguments
    grid = slice(ALL_FIELDS.index("grid_frame"), ALL_FIELDS.index("grid_cells") + 1)
    first, again = with_derived(arguments, distance_grid_cells), with_derived(arguments, distance_grid_cells)
    assert all(a is b for a, b in zip(first[grid], again[grid], strict=True))
    moved = list(arguments)
    centers = VALIDITY_FIELDS.index("box_centers")
    moved[centers] = moved[centers] + np.array([0.0, 0.0, 0.05])  # every obstacle 5 cm up
    for name in ("box_lows", "box_highs"):
        moved[VALIDITY_FIELDS.index(name)] = moved[VALIDITY_FIELDS.index(name)] + np.array([0.0, 0.0, 0.05])
    other = with_derived(tuple(moved), distance_grid_cells)
    assert other[grid][2] is not first[grid][2]
    assert other[grid][0][2] == pytest.approx(first[grid][0][2] + 0.05)  # the grid moved with them
