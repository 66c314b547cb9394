"""The screen in SIMD lanes in front of the validity kernel: eight doubles as one value do the
arithmetic numpy does, and a configuration the screen clears is one the kernel accepts, so the
first invalid row of a batch is the kernel's."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any, NamedTuple

import numba
import numpy as np
import pytest

from kitchen_tamp.motion.geometry.primitive_scene import PrimitiveObstacle, arm_among_obstacles
from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.codes import FIXED, PRISMATIC, REVOLUTE, REVOLUTE_Z, SKIPPED
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.buffers import lane_buffers
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.kinematics import LANES, lane_link_poses
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.screen import (
    first_invalid_in_lanes,
    lanes_cleared,
)
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.simd import (
    abs8,
    at_least8,
    floor8,
    gather8,
    less8,
    load8,
    max8,
    min8,
    sqrt8,
    store8,
)
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import folded_link_poses
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import validity_scratch
from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import origin_axes
from kitchen_tamp.motion.motion_bench_maker import mbm_panda
from kitchen_tamp.world import panda_urdf_path
from tests.motion.poses import pose, rotation


class Chain(NamedTuple):
    """The links' fields `lane_link_poses` reads (a `ValidityArrays` in the screen), in the order
    `folded_link_poses` takes them."""

    root: np.ndarray
    parents: np.ndarray
    origins: np.ndarray
    kinds: np.ndarray
    axes: np.ndarray
    variables: np.ndarray
    origin_axes: np.ndarray


LANE_POSES: Any = lane_link_poses
FOLDED_POSES: Any = folded_link_poses
"""The compiled kernels, untyped for mypy (numba's dispatcher stubs take no argument list)."""


@numba.njit(cache=True)
def _arithmetic(a: Any, b: Any, cells: Any, out: Any) -> tuple[int, int]:
    x, y = load8(a, 0), load8(b, 0)
    store8(out, 0, (x + y) * 2.0 - x / y)
    store8(out, 8, -x * y + 1.0)
    store8(out, 16, floor8(x) + sqrt8(abs8(y)))
    store8(out, 24, min8(x, y) - max8(x, 0.5))
    store8(out, 32, gather8(cells, floor8(abs8(x) * 3.0)))
    return less8(x, y), at_least8(x, 0.0)


def test_eight_doubles_do_numpys_arithmetic() -> None:
    rng = np.random.default_rng(3)
    a, b = rng.uniform(-2.0, 2.0, 8), rng.uniform(0.5, 3.0, 8)
    cells = rng.integers(0, 255, 8, dtype=np.uint8)
    out = np.empty(40)
    below, nonnegative = _arithmetic(a, b, cells, out)
    np.testing.assert_allclose(out[:8], (a + b) * 2.0 - a / b, rtol=1e-15)
    np.testing.assert_allclose(out[8:16], -a * b + 1.0, rtol=1e-15)
    np.testing.assert_allclose(out[16:24], np.floor(a) + np.sqrt(np.abs(b)), rtol=1e-15)
    np.testing.assert_allclose(out[24:32], np.minimum(a, b) - np.maximum(a, 0.5), rtol=1e-15)
    assert np.array_equal(out[32:], cells[np.floor(np.abs(a) * 3.0).astype(int)])
    assert below == sum(1 << k for k in range(8) if a[k] < b[k])
    assert nonnegative == sum(1 << k for k in range(8) if a[k] >= 0.0)


OBSTACLES = (
    PrimitiveObstacle("table", "box", np.array([0.6, 0.9, 0.04]), pose((0.5, 0.0, 0.1), (0.0, 0.0, 0.2))),
    PrimitiveObstacle("board", "box", np.array([0.25, 0.02, 0.3]), pose((0.35, 0.35, 0.5), (0.4, 0.3, 0.8))),
    PrimitiveObstacle("can", "cylinder", np.array([0.05, 0.2]), pose((0.45, -0.35, 0.3), (0.9, 0.0, 0.3))),
    PrimitiveObstacle("ball", "sphere", np.array([0.07]), pose((0.25, -0.45, 0.65), (0.0, 0.0, 0.0))),
)


@pytest.fixture(scope="module")
def spheres(tmp_path_factory: pytest.TempPathFactory) -> Iterator[SphereCollisionChecker]:
    scene = arm_among_obstacles(mbm_panda(panda_urdf_path(), ()), OBSTACLES, tmp_path_factory.mktemp("urdf"))
    yield SphereCollisionChecker(scene)


@numba.njit(cache=True)
def _screened(qs: Any, arrays: Any, margin: float) -> Any:
    """Per row: whether the screen clears it."""
    lanes = lane_buffers(arrays, qs.shape[1])
    cleared = np.zeros(qs.shape[0], dtype=np.bool_)
    for first in range(0, qs.shape[0], LANES):
        bits = lanes_cleared(qs, first, arrays, margin, lanes)
        for lane in range(min(LANES, qs.shape[0] - first)):
            cleared[first + lane] = bits >> lane & 1
    return cleared


def _along_segments(rng: np.random.Generator, lower: np.ndarray, upper: np.ndarray, count: int) -> np.ndarray:
    """Configurations 0.01 rad apart along random 1 rad steps: neighbours, as a segment's batch."""
    starts = rng.uniform(lower, upper, size=(count, len(lower)))
    steps = rng.normal(size=starts.shape)
    steps /= np.linalg.norm(steps, axis=1, keepdims=True)
    shares = np.linspace(0.0, 1.0, 100)
    rows = starts[:, np.newaxis, :] + shares[np.newaxis, :, np.newaxis] * steps[:, np.newaxis, :]
    return np.ascontiguousarray(np.clip(rows.reshape(-1, len(lower)), lower, upper))


def _cases(checker: SphereCollisionChecker, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    uniform = rng.uniform(checker.lower, checker.upper, size=(4000, 7))
    return np.concatenate([uniform, _along_segments(rng, checker.lower, checker.upper, 300)])


@pytest.mark.parametrize("margin_change", [0.0, 0.02, -0.005])
def test_a_configuration_the_screen_clears_is_one_the_kernel_accepts(
    spheres: SphereCollisionChecker, margin_change: float
) -> None:
    arrays, margin = spheres.compiled_validity()
    margin += margin_change  # the pair tables used for both proofs, one, or neither
    qs = _cases(spheres, 5)
    valid = valid_rows(qs, arrays, margin, False, validity_scratch(arrays, 7))
    cleared = _screened(qs, arrays, margin)
    assert not np.any(cleared & ~valid)
    assert 0.2 < valid.mean() < 0.95  # the obstacles are in the arm's way
    assert cleared[valid].mean() > 0.8  # and the screen clears most free configurations


def test_the_screen_clears_configurations_beside_the_table_of_motion_bench_maker(mbm_table: Any) -> None:
    _, checker, _ = mbm_table
    arrays, margin = checker.compiled_validity()
    qs = _cases(checker, 6)
    valid = valid_rows(qs, arrays, margin, False, validity_scratch(arrays, 7))
    cleared = _screened(qs, arrays, margin)
    assert not np.any(cleared & ~valid)
    assert cleared[valid].mean() > 0.9


def test_the_first_invalid_row_of_a_batch_is_the_kernels(spheres: SphereCollisionChecker) -> None:
    arrays, margin = spheres.compiled_validity()
    qs = _along_segments(np.random.default_rng(8), spheres.lower, spheres.upper, 80)
    scratch, lanes = validity_scratch(arrays, 7), lane_buffers(arrays, 7)
    firsts = []
    for batch in np.split(qs, 160):  # batches of 50 rows: six lanes' worth and a partial one
        valid = valid_rows(batch, arrays, margin, False, scratch)
        expected = int(np.argmin(valid)) if not valid.all() else -1
        assert first_invalid_in_lanes(np.ascontiguousarray(batch), arrays, margin, scratch, lanes) == expected
        firsts.append(expected)
    assert -1 in firsts and any(first > LANES for first in firsts)  # free batches and late collisions


def test_the_lanes_place_every_kind_of_link_where_the_kernel_does() -> None:
    """A chain of every joint kind the folded layout holds (fixed, revolute about a tilted axis,
    about z behind arbitrary and quarter-turn origins, prismatic, a skipped link): eight
    configurations' poses in lanes are the kernel's, one configuration at a time."""
    rng = np.random.default_rng(35)
    kinds = np.array([FIXED, REVOLUTE, REVOLUTE_Z, SKIPPED, PRISMATIC, REVOLUTE_Z, FIXED], dtype=np.int64)
    parents = np.array([-1, 0, 1, 2, 2, 4, 5], dtype=np.int64)
    variables = np.array([-1, 0, 1, -1, 2, 3, -1], dtype=np.int64)
    axes = np.zeros((len(kinds), 3))
    axes[1], axes[2], axes[4], axes[5] = [0.6, 0.0, 0.8], [0.0, 0.0, 1.0], [0.0, 0.6, -0.8], [0.0, 0.0, 1.0]
    origins = np.stack([rotation(rng.normal(size=3), rng.uniform(-3, 3)) for _ in range(len(kinds))])
    origins[5, :3, :3] = [[0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]  # quarter turns
    origins[:, :3, 3] = rng.normal(size=(len(kinds), 3))
    chain = Chain(origins[0].copy(), parents, origins, kinds, axes, variables, origin_axes(origins, kinds))
    assert chain.origin_axes[5, 0] != 0 and not chain.origin_axes[2].any()  # both paths of a joint about z
    qs = rng.uniform(-3.5, 3.5, size=(LANES, 4))
    in_lanes = np.full(len(kinds) * 12 * LANES, np.nan)
    LANE_POSES(
        chain, np.ascontiguousarray(qs.T).reshape(-1), np.empty(4 * LANES), np.empty(4 * LANES), in_lanes
    )
    in_lanes = in_lanes.reshape(len(kinds), 3, 4, LANES)
    poses, frame = np.full((len(kinds), 3, 4), np.nan), np.empty((3, 4))
    sines, cosines = np.empty(4), np.empty(4)
    for m in range(LANES):
        FOLDED_POSES(qs, m, *chain, poses, frame, sines, cosines)
        kept = kinds != SKIPPED
        np.testing.assert_allclose(in_lanes[kept, :, :, m], poses[kept], rtol=0.0, atol=1e-13)
    assert np.all(np.isnan(in_lanes[3]))
