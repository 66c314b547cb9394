"""A robot among boxes, spheres and cylinders: the sphere model measures each exactly and never
calls free what Drake's exact model finds colliding."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.joint_spacing import interior_fractions, interval_count
from kitchen_tamp.motion import CountingSegmentChecker
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.primitive_scene import PrimitiveObstacle, arm_among_obstacles, rotation_rpy
from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.codes import SHAPE_BOX, SHAPE_CYLINDER, SHAPE_SPHERE
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import box_gap_at
from kitchen_tamp.motion.geometry.spheres.kernels.segments import (
    coarse_to_fine_fractions,
    free_prefix_checked_in,
    segment_checked_in,
)
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import validity_scratch
from kitchen_tamp.motion.geometry.urdf import rpy_matrix
from kitchen_tamp.motion.motion_bench_maker import mbm_panda
from kitchen_tamp.world import panda_urdf_path
from tests.motion.poses import pose

VALID_ROWS: Any = valid_rows
"""The compiled kernels, untyped for mypy (numba's dispatcher stubs take no argument list)."""
SEGMENT_IN: Any = segment_checked_in
FREE_PREFIX_IN: Any = free_prefix_checked_in
SELF_PAIRS = (("panda_hand", "panda_link0"), ("panda_link0", "panda_link5"), ("panda_link1", "panda_link7"))


OBSTACLES = (
    PrimitiveObstacle("pillar", "cylinder", np.array([0.06, 0.9]), pose((0.45, 0.0, 0.45))),
    PrimitiveObstacle(
        "lying can", "cylinder", np.array([0.05, 0.4]), pose((0.3, 0.35, 0.5), (1.2, 0.3, 0.4))
    ),
    PrimitiveObstacle("ball", "sphere", np.array([0.12]), pose((0.1, -0.45, 0.6))),
    PrimitiveObstacle("shelf", "box", np.array([0.3, 0.6, 0.02]), pose((0.35, -0.2, 0.25), (0.0, 0.1, 0.5))),
)


@pytest.fixture(scope="module")
def models(
    tmp_path_factory: pytest.TempPathFactory,
) -> Iterator[tuple[SphereCollisionChecker, DrakeCollisionChecker]]:
    scene = arm_among_obstacles(
        mbm_panda(panda_urdf_path(), SELF_PAIRS), OBSTACLES, tmp_path_factory.mktemp("urdf")
    )
    yield SphereCollisionChecker(scene), DrakeCollisionChecker(scene)


def test_rpy_round_trips_a_rotation() -> None:
    rng = np.random.default_rng(3)
    for rpy in [*rng.uniform(-3.0, 3.0, size=(50, 3)), (0.3, np.pi / 2, -1.0), (0.2, -np.pi / 2, 0.7)]:
        rotation = rpy_matrix(np.array(rpy))
        assert np.allclose(rpy_matrix(np.array(rotation_rpy(rotation))), rotation, atol=1e-12)


def test_gaps_to_boxes_spheres_and_cylinders_are_exact_signed_distances() -> None:
    rng = np.random.default_rng(5)
    rotation = rpy_matrix(np.array([0.4, -0.7, 1.1]))
    rotations, centers = rotation[None].copy(), np.array([[0.1, -0.2, 0.3]])
    halves = np.array([[0.2, 0.2, 0.5]])  # the cylinder's radius, radius and half length
    for point in rng.uniform(-1.0, 1.0, size=(300, 3)):
        local = rotation.T @ (point - centers[0])
        radial, axial = np.hypot(local[0], local[1]) - 0.2, abs(local[2]) - 0.5
        cylinder = (
            np.hypot(max(radial, 0.0), max(axial, 0.0)) if max(radial, axial) > 0 else max(radial, axial)
        )
        box_excess = np.abs(local) - halves[0]
        box = np.linalg.norm(np.maximum(box_excess, 0.0)) if box_excess.max() > 0 else box_excess.max()
        sphere = np.linalg.norm(point - centers[0]) - 0.2
        for kind, expected in ((SHAPE_CYLINDER, cylinder), (SHAPE_BOX, box), (SHAPE_SPHERE, sphere)):
            kinds = np.array([kind], dtype=np.int64)
            gap = box_gap_at(point[0], point[1], point[2], rotations, centers, halves, kinds, 0)
            assert gap == pytest.approx(expected, abs=1e-12)


def _near_contact(exact: DrakeCollisionChecker, qs: np.ndarray) -> np.ndarray:
    """Configurations within about 1e-4 rad of Drake's contact: free/colliding pairs bisected."""
    valid = exact.is_valid(qs)
    count = min(int(valid.sum()), int((~valid).sum()))
    free, colliding = qs[valid][:count], qs[~valid][:count]
    for _ in range(14):
        middle = (free + colliding) / 2.0
        middle_valid = exact.is_valid(middle)[:, None]
        free, colliding = np.where(middle_valid, middle, free), np.where(middle_valid, colliding, middle)
    return np.concatenate([free, colliding])


@pytest.mark.slow
def test_no_configuration_drake_finds_colliding_is_free_for_the_spheres(
    models: tuple[SphereCollisionChecker, DrakeCollisionChecker],
) -> None:
    spheres, exact = models
    rng = np.random.default_rng(11)
    uniform = rng.uniform(spheres.lower, spheres.upper, size=(3000, 7))
    samples = np.concatenate([uniform, _near_contact(exact, uniform[:800])])
    sphere_valid, exact_valid = spheres.is_valid(samples), exact.is_valid(samples)
    assert not np.any(sphere_valid & ~exact_valid)
    assert 0.2 < exact_valid[:3000].mean() < 0.95  # the obstacles are in the arm's way
    assert np.mean(sphere_valid[:3000] == exact_valid[:3000]) > 0.85  # and not by their bounding boxes
    picked = rng.choice(len(samples), size=300, replace=False)  # the numpy reference is slow
    assert np.array_equal(sphere_valid[picked], spheres.is_valid_uncompiled(samples[picked]))


def test_the_first_invalid_row_is_the_first_false_verdict(
    models: tuple[SphereCollisionChecker, DrakeCollisionChecker],
) -> None:
    spheres, _ = models
    rng = np.random.default_rng(12)
    for _ in range(20):
        qs = rng.uniform(spheres.lower, spheres.upper, size=(int(rng.integers(1, 40)), 7))
        valid = spheres.is_valid(qs)
        expected = None if valid.all() else int(np.argmin(valid))
        assert spheres.first_invalid(qs) == expected
    assert spheres.first_invalid(np.zeros((0, 7))) is None


def test_the_urdf_is_written_once_per_content(tmp_path: Path) -> None:
    arm = mbm_panda(panda_urdf_path(), SELF_PAIRS)
    first = arm_among_obstacles(arm, OBSTACLES, tmp_path).bodies[1].urdf_path
    again = arm_among_obstacles(arm, OBSTACLES, tmp_path).bodies[1].urdf_path
    other = arm_among_obstacles(arm, OBSTACLES[:2], tmp_path).bodies[1].urdf_path
    assert first == again != other
    assert len(list(tmp_path.glob("*.urdf"))) == 2


class _RowsOnly:
    """The sphere model seen through ``is_valid`` alone (the batch-by-batch path)."""

    def __init__(self, checker: SphereCollisionChecker) -> None:
        self.checker = checker

    def is_valid(self, qs: np.ndarray) -> np.ndarray:
        return self.checker.is_valid(qs)

    def segment_valid(self, q0: np.ndarray, q1: np.ndarray) -> bool:
        raise NotImplementedError


@pytest.mark.slow
def test_compiled_segments_check_what_the_batches_check_and_count_alike(
    models: tuple[SphereCollisionChecker, DrakeCollisionChecker],
) -> None:
    spheres, _ = models
    rng = np.random.default_rng(13)
    compiled, batched = (
        CountingSegmentChecker(spheres, 0.01),
        CountingSegmentChecker(_RowsOnly(spheres), 0.01),
    )
    for _ in range(150):
        q0, q1 = rng.uniform(spheres.lower, spheres.upper, size=(2, 7))
        q1 = q0 + (q1 - q0) * rng.uniform(0.0, 0.6)
        ends = tuple(bool(b) for b in rng.integers(0, 2, size=2))
        assert compiled.segment_valid(
            q0, q1, check_start=ends[0], check_end=ends[1]
        ) == batched.segment_valid(q0, q1, check_start=ends[0], check_end=ends[1])
        for block in (1, 7, 100):
            assert compiled.free_prefix_length(q0, q1, block) == batched.free_prefix_length(q0, q1, block)
        assert compiled.configurations_checked == batched.configurations_checked


def test_compiled_fractions_are_the_joint_spacing_rule() -> None:
    for length in np.linspace(0.001, 3.0, 400):
        start, end = np.zeros(1), np.array([length])
        intervals = interval_count(start, end, 0.01)
        assert np.array_equal(coarse_to_fine_fractions(intervals), interior_fractions(start, end, 0.01))


def test_one_scratch_serves_many_calls_with_each_calls_verdicts(
    models: tuple[SphereCollisionChecker, DrakeCollisionChecker],
) -> None:
    """The kernels working in one `validity_scratch` over many batches and segments (as the
    compiled RRT-Connect loop does) give every call the verdicts of a fresh call, and the batches
    the numpy reference's."""
    spheres, _ = models
    arrays, margin = spheres.compiled_validity()
    rng = np.random.default_rng(3)
    scratch = validity_scratch(arrays, 7)
    for size in [1, 2, 5, 1, 17, 3, 1, 40, 1, 8] * 5:
        qs = rng.uniform(spheres.lower, spheres.upper, size=(size, 7))
        reused = VALID_ROWS(qs, arrays, margin, False, scratch)
        assert np.array_equal(reused, spheres.is_valid(qs))
        assert np.array_equal(reused, spheres.is_valid_uncompiled(qs))
    for _ in range(60):
        q0, q1 = rng.uniform(spheres.lower, spheres.upper, size=(2, 7))
        q1 = q0 + (q1 - q0) * rng.uniform(0.0, 0.6)
        intervals = interval_count(q0, q1, 0.01)
        assert SEGMENT_IN(q0, q1, intervals, True, True, arrays, margin, scratch) == spheres.segment_checked(
            q0, q1, intervals, True, True
        )
        distance = float(np.linalg.norm(q1 - q0))
        in_scratch = FREE_PREFIX_IN(q0, q1, distance, 0.01, 30, arrays, margin, scratch)
        assert in_scratch == spheres.free_prefix_checked(q0, q1, distance, 0.01, 30)
