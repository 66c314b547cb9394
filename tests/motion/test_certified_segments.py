"""Segment checks that skip what a clearance bound proves free: the same verdicts as checking every
configuration, on a MotionBenchMaker table (with pair tables) and among boxes, spheres and
cylinders; bounds on how fast the spheres move that hold; far fewer configurations checked."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.joint_spacing import interval_count
from kitchen_tamp.motion.geometry.primitive_scene import arm_among_obstacles
from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.certified_segments import (
    certified_free_prefix_checked_in,
    certified_segment_checked_in,
    group_speeds,
)
from kitchen_tamp.motion.geometry.spheres.kernels.segments import free_prefix_checked_in, segment_checked_in
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import validity_scratch
from kitchen_tamp.motion.geometry.spheres.reference import sphere_world_centers
from kitchen_tamp.motion.motion_bench_maker import mbm_panda, mbm_scene, read_mbm_problem
from kitchen_tamp.world import panda_urdf_path
from tests.motion.test_motion_bench_maker import TABLE_REQUEST, TABLE_SCENE
from tests.motion.test_primitive_scene import OBSTACLES, SELF_PAIRS

SEGMENT: Any = segment_checked_in
"""The compiled kernels, untyped for mypy (numba's dispatcher stubs take no argument list)."""
FREE_PREFIX: Any = free_prefix_checked_in
CERTIFIED_SEGMENT: Any = certified_segment_checked_in
CERTIFIED_FREE_PREFIX: Any = certified_free_prefix_checked_in
SPEEDS: Any = group_speeds
RESOLUTION = 0.01


@pytest.fixture(scope="module", params=["mbm table", "primitives"])
def spheres(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Iterator[Any]:
    if request.param == "mbm table":
        problem = read_mbm_problem("table_pick", 7, TABLE_SCENE, TABLE_REQUEST)
        scene = mbm_scene(problem, panda_urdf_path(), Path(tmp_path_factory.mktemp("table")))
    else:
        panda = mbm_panda(panda_urdf_path(), SELF_PAIRS)
        scene = arm_among_obstacles(panda, OBSTACLES, tmp_path_factory.mktemp("primitives"))
    yield SphereCollisionChecker(scene)


def _segments(spheres: SphereCollisionChecker, count: int, seed: int) -> Iterator[tuple[Any, Any]]:
    """Segments from valid configurations: long ones, and short ones ending near a colliding one
    (where the bounds fail and the walk falls back on checking)."""
    rng = np.random.default_rng(seed)
    samples = rng.uniform(spheres.lower, spheres.upper, size=(6 * count, 7))
    valid = spheres.is_valid(samples)
    free, colliding = samples[valid], samples[~valid]
    for i in range(count):
        q0 = free[i]
        yield q0, q0 + (free[i + count] - q0) * rng.uniform(0.1, 1.0)
        yield q0, q0 + (colliding[i] - q0) * rng.uniform(0.3, 1.2)


def test_certified_checks_give_every_configurations_verdicts_from_fewer(spheres: Any) -> None:
    arrays, margin = spheres.compiled_validity()
    scratch = validity_scratch(arrays, 7)
    dense_total = certified_total = 0
    verdicts = set()
    for q0, q1 in _segments(spheres, 60, seed=4):
        q1 = np.clip(q1, spheres.lower, spheres.upper)
        intervals = interval_count(q0, q1, RESOLUTION)
        for check_end in (False, True):
            dense = SEGMENT(q0, q1, intervals, False, check_end, arrays, margin, scratch)
            certified = CERTIFIED_SEGMENT(q0, q1, intervals, False, check_end, arrays, margin, scratch)
            assert certified[0] == dense[0]
            verdicts.add(dense[0])
        distance = float(np.linalg.norm(q1 - q0))
        dense_prefix = FREE_PREFIX(q0, q1, distance, RESOLUTION, arrays, margin, scratch)
        certified_prefix = CERTIFIED_FREE_PREFIX(q0, q1, distance, RESOLUTION, arrays, margin, scratch)
        assert certified_prefix[0] == dense_prefix[0]
        dense_total += dense_prefix[1]
        certified_total += certified_prefix[1]
    assert verdicts == {True, False}
    assert certified_total < dense_total / 2


def test_an_end_outside_the_limits_is_checked_configuration_by_configuration(spheres: Any) -> None:
    """No bound is trusted on a segment leaving the joint box: the walk checks every configuration
    and finds the first one outside, as the dense check does."""
    arrays, margin = spheres.compiled_validity()
    scratch = validity_scratch(arrays, 7)
    q0 = np.array([0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785])
    q1 = q0.copy()
    q1[0] = spheres.upper[0] + 0.3
    distance = float(np.linalg.norm(q1 - q0))
    dense = FREE_PREFIX(q0, q1, distance, RESOLUTION, arrays, margin, scratch)
    certified = CERTIFIED_FREE_PREFIX(q0, q1, distance, RESOLUTION, arrays, margin, scratch)
    assert certified[0] == dense[0] < distance


def test_spheres_move_no_faster_than_their_bounds(spheres: Any) -> None:
    """Along random straight motions, no coarse sphere moves further than its group's speed bound,
    and no two spheres of a self pair come closer faster than the pair's."""
    arrays, _ = spheres.compiled_validity()
    model = spheres.model
    groups = len(model.groups)
    rng = np.random.default_rng(11)
    speeds, pair_speeds = np.empty(groups), np.empty(len(model.group_pairs))
    for _ in range(40):
        q0 = rng.uniform(spheres.lower, spheres.upper)
        q1 = np.clip(q0 + rng.normal(0.0, 0.6, size=7), spheres.lower, spheres.upper)
        SPEEDS(q0, q1, arrays, speeds, pair_speeds)
        ts = np.linspace(0.0, 1.0, 201)
        world = sphere_world_centers(model, q0 + ts[:, None] * (q1 - q0))  # (T, S, 3)
        step = ts[1] - ts[0]
        for g, group in enumerate(model.groups):
            moved = np.linalg.norm(np.diff(world[:, group.spheres], axis=0), axis=-1)
            assert moved.max() <= speeds[g] * step * (1.0 + 1e-6) + 1e-12
        for k, (g, h) in enumerate(model.group_pairs):
            first, second = world[:, model.groups[g].spheres], world[:, model.groups[h].spheres]
            apart = np.linalg.norm(first[:, :, None] - second[:, None], axis=-1)
            assert np.abs(np.diff(apart, axis=0)).max() <= pair_speeds[k] * step * (1.0 + 1e-6) + 1e-12
