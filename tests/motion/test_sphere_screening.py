"""Spheres in front of an exact model in the real kitchen: verdicts are the exact model's (Drake's
or PyBullet's), a batch's first collision is found without asking the exact model about the rows
after it, and against Drake's bare meshes the spheres' mesh padding is taken back soundly."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.motion import CountingSegmentChecker
from kitchen_tamp.motion.collision_checker import JointConfigurations, ValidityMask
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.covering import SphereSet, covering_slack, sample_polytope
from kitchen_tamp.motion.geometry.spheres.scene import PYBULLET_MESH_MARGIN, shape_polytope
from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker
from kitchen_tamp.motion.geometry.urdf import read_urdf
from kitchen_tamp.world import PyBulletCollisionChecker
from kitchen_tamp.world.scene_description import describe_collision_checker

PLANNING_MARGIN = 0.003


class CountingExact:
    """An exact model that counts the configurations it is asked about."""

    def __init__(self, exact: DrakeCollisionChecker) -> None:
        self.exact = exact
        self.asked = 0

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        self.asked += len(qs)
        return self.exact.is_valid(qs)

    def segment_valid(self, q0: np.ndarray, q1: np.ndarray) -> bool:
        return self.exact.segment_valid(q0, q1)


@pytest.fixture(scope="module")
def pybullet(kitchen: KitchenScene) -> PyBulletCollisionChecker:
    return kitchen.collision_checker()


@pytest.fixture(scope="module")
def spheres(pybullet: PyBulletCollisionChecker) -> SphereCollisionChecker:
    return SphereCollisionChecker(describe_collision_checker(pybullet), margin=PLANNING_MARGIN)


@pytest.fixture(scope="module")
def drake(pybullet: PyBulletCollisionChecker) -> DrakeCollisionChecker:
    return DrakeCollisionChecker(describe_collision_checker(pybullet), margin=PLANNING_MARGIN)


def test_first_invalid_is_the_exact_models_first_collision_and_asks_no_further(
    spheres: SphereCollisionChecker, drake: DrakeCollisionChecker
) -> None:
    counting = CountingExact(drake)
    screened = SphereScreenedChecker(spheres, counting)
    rng = np.random.default_rng(11)
    found = 0
    for _ in range(30):
        qs = rng.uniform(drake.lower, drake.upper, size=(6, 7))
        exact = drake.is_valid(qs)
        expected = None if exact.all() else int(np.argmin(exact))
        counting.asked = 0
        assert screened.first_invalid(qs) == expected
        rejected = np.flatnonzero(~spheres.is_valid(qs))
        asked = len(rejected) if expected is None else int(np.searchsorted(rejected, expected)) + 1
        assert counting.asked == asked
        found += expected is not None
    assert 0 < found < 30


def test_segment_checks_through_the_finder_match_whole_batch_verdicts(
    spheres: SphereCollisionChecker, drake: DrakeCollisionChecker
) -> None:
    screened = SphereScreenedChecker(spheres, drake)
    finder, whole = CountingSegmentChecker(screened, 0.01), CountingSegmentChecker(drake, 0.01)
    rng = np.random.default_rng(12)
    q0s = rng.uniform(drake.lower, drake.upper, size=(40, 7))
    q0s = q0s[drake.is_valid(q0s)][:12]
    q1s = q0s + rng.normal(scale=0.6, size=q0s.shape)
    q1s = np.clip(q1s, drake.lower, drake.upper)
    verdicts = []
    for q0, q1 in zip(q0s, q1s, strict=True):
        verdicts.append(finder.segment_valid(q0, q1))
        assert verdicts[-1] == whole.segment_valid(q0, q1)
        assert finder.free_prefix_length(q0, q1) == whole.free_prefix_length(q0, q1)
    assert finder.configurations_checked == whole.configurations_checked
    assert any(verdicts) and not all(verdicts)


def test_spheres_at_the_simulators_margin_screen_pybullet_to_its_own_verdicts(
    spheres: SphereCollisionChecker, pybullet: PyBulletCollisionChecker
) -> None:
    screened = SphereScreenedChecker(spheres.with_margin(pybullet.margin), pybullet)
    qs = np.random.default_rng(13).uniform(pybullet.lower, pybullet.upper, size=(300, 7))
    verdicts = screened.is_valid(qs)
    assert verdicts.tolist() == pybullet.is_valid(qs).tolist()
    assert 0 < screened.exact_checks < len(qs)
    assert spheres.margin == PLANNING_MARGIN  # the twin did not change the planning model


def test_exact_verdicts_are_remembered_by_configuration(
    spheres: SphereCollisionChecker, drake: DrakeCollisionChecker
) -> None:
    counting = CountingExact(drake)
    screened = SphereScreenedChecker(spheres, counting)
    qs = np.random.default_rng(14).uniform(drake.lower, drake.upper, size=(40, 7))
    first = screened.is_valid(qs)
    asked = counting.asked
    assert asked == int(np.count_nonzero(~spheres.is_valid(qs))) > 0
    assert screened.is_valid(qs).tolist() == first.tolist() == drake.is_valid(qs).tolist()
    assert screened.first_invalid(qs) == (None if first.all() else int(np.argmin(first)))
    assert counting.asked == asked == screened.exact_checks


def near_drakes_contact(drake: DrakeCollisionChecker, count: int, rng: np.random.Generator) -> np.ndarray:
    """Configurations on both sides of Drake's margin, bisected between a valid and an invalid sample."""
    qs = rng.uniform(drake.lower, drake.upper, size=(4 * count, 7))
    valid = drake.is_valid(qs)
    count = min(count, int(valid.sum()), int((~valid).sum()))
    free, colliding = qs[valid][:count], qs[~valid][:count]
    for _ in range(10):
        middle = (free + colliding) / 2.0
        middle_valid = drake.is_valid(middle)
        free = np.where(middle_valid[:, None], middle, free)
        colliding = np.where(middle_valid[:, None], colliding, middle)
    return np.concatenate([free, colliding])


def test_the_padding_taken_back_was_added_to_cover_the_hulls(
    spheres: SphereCollisionChecker, pybullet: PyBulletCollisionChecker
) -> None:
    model, robot = spheres.model, read_urdf(kitchen_robot_urdf(pybullet))
    rng = np.random.default_rng(15)
    robot_groups = [g for g, group in enumerate(model.groups) if group.role != "carried"]
    assert robot_groups and all(spheres.padding[g] == PYBULLET_MESH_MARGIN for g in robot_groups)
    for g in robot_groups:
        group = model.groups[g]
        for centers, radii in (  # both levels: the coarse spheres and the tight (fine) covering
            (model.sphere_centers[group.spheres], model.sphere_radii[group.spheres]),
            (model.fine_centers[group.fine_spheres], model.fine_radii[group.fine_spheres]),
        ):
            assert len(radii) > 0
            bare = SphereSet(centers, radii - spheres.padding[g])
            for shape in robot.collisions:
                if shape.link == group.link:
                    assert covering_slack(bare, sample_polytope(shape_polytope(shape), 400, rng)) >= -1e-9


def kitchen_robot_urdf(pybullet: PyBulletCollisionChecker) -> str:
    description = describe_collision_checker(pybullet)
    return next(body.urdf_path for body in description.bodies if body.name == description.robot)


def test_without_padding_the_spheres_never_accept_what_drake_rejects(
    spheres: SphereCollisionChecker, drake: DrakeCollisionChecker
) -> None:
    rng = np.random.default_rng(16)
    random = rng.uniform(drake.lower, drake.upper, size=(1500, 7))
    taken_back = 0
    for qs in (near_drakes_contact(drake, 150, rng), random):
        exact, bare, padded = drake.is_valid(qs), spheres.is_valid_without_padding(qs), spheres.is_valid(qs)
        assert not np.any(bare & ~exact)
        assert np.all(bare | ~padded)  # taking the padding back only accepts more
        taken_back += int(np.count_nonzero(bare & ~padded))
    assert taken_back > 0
    screened = SphereScreenedChecker(spheres, drake, exact_is_bare=True)
    assert screened.is_valid(qs).tolist() == exact.tolist()
    assert screened.exact_checks < np.count_nonzero(~padded)
