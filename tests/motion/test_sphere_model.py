"""The sphere model of the real kitchen: spheres cover the Panda's collision hulls, its batch
kinematics is PyBullet's, it never calls free what PyBullet finds colliding, its gradients are the
finite-difference ones, and it is built from what the simulator loaded (no drift)."""

from __future__ import annotations

import numpy as np
import pybullet as p
import pytest

from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.covering import (
    SphereSet,
    box_polytope,
    cover_with_spheres,
    covering_slack,
    overshoot,
    sample_polytope,
)
from kitchen_tamp.motion.geometry.spheres.scene import _covered_shape, shape_polytope
from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker
from kitchen_tamp.motion.geometry.spheres.tight_covering import (
    TIGHT_COVERING_TOLERANCE,
    cover_tightly,
    verify_covering,
)
from kitchen_tamp.motion.geometry.urdf import read_urdf
from kitchen_tamp.world import panda_urdf_path
from kitchen_tamp.world.scene_description import describe_collision_checker
from tests.motion.conftest import CheckerPair, free_hand_pair, holding_spam_pair, twin

RANDOM_CONFIGURATIONS = 2000
NEAR_CONFIGURATIONS = 300


SpherePair = CheckerPair[SphereCollisionChecker]


@pytest.fixture(scope="module")
def free(kitchen: KitchenScene) -> SpherePair:
    return free_hand_pair(kitchen, SphereCollisionChecker)


@pytest.fixture(scope="module")
def holding(kitchen: KitchenScene) -> SpherePair:
    return holding_spam_pair(kitchen, SphereCollisionChecker)


def test_spheres_cover_every_panda_collision_hull() -> None:
    """Both levels (coarse and tight, as cached on disk) cover every hull, and the tight level
    reaches outside it by about its tolerance at most."""
    model = read_urdf(panda_urdf_path())
    rng = np.random.default_rng(0)
    assert any(shape.kind == "mesh" for shape in model.collisions)
    for index, shape in enumerate(model.collisions):
        polytope = shape_polytope(shape)
        points = sample_polytope(polytope, 1500, rng)
        for tolerance, tight in ((0.012, False), (TIGHT_COVERING_TOLERANCE, True)):
            spheres = _covered_shape(model.path, index, tolerance, tight)
            slack = covering_slack(spheres, points)
            assert slack >= -1e-9, (shape.link, tight, slack)
        planes = polytope.planes()
        reaches = [overshoot(c, r, planes) for c, r in zip(spheres.centers, spheres.radii, strict=True)]
        assert np.median(reaches) < 1.5 * TIGHT_COVERING_TOLERANCE, shape.link
        assert max(reaches) < 0.02, shape.link


@pytest.mark.slow
def test_tight_covering_is_proved_and_repaired() -> None:
    """Fresh from the generator: a finger and a box are covered with every sphere reaching a few
    millimetres out; a covering with a sphere taken away fails on sampled points, and the
    verification grows spheres until it covers again."""
    model = read_urdf(panda_urdf_path())
    finger = next(shape for shape in model.collisions if shape.link == "panda_leftfinger")
    rng = np.random.default_rng(1)
    for polytope in (shape_polytope(finger), box_polytope(np.array([0.1, 0.05, 0.085]))):
        spheres = cover_tightly(polytope)
        points = sample_polytope(polytope, 3000, rng)
        assert covering_slack(spheres, points) >= -1e-9
        planes = polytope.planes()
        reaches = [overshoot(c, r, planes) for c, r in zip(spheres.centers, spheres.radii, strict=True)]
        assert max(reaches) < 0.012
        largest = int(np.argmax(spheres.radii))
        keep = np.arange(len(spheres)) != largest
        holed = SphereSet(spheres.centers[keep], spheres.radii[keep])
        assert covering_slack(holed, points) < 0.0
        repaired, report = verify_covering(polytope, holed, cell_size=4 * TIGHT_COVERING_TOLERANCE)
        assert report.grown > 0
        assert covering_slack(repaired, points) >= -1e-9


def test_generated_spheres_cover_and_stay_close() -> None:
    """Fresh from the generator (not the disk cache): a finger mesh and a box are covered, and no
    sphere reaches more than a few centimetres outside."""
    model = read_urdf(panda_urdf_path())
    finger = next(shape for shape in model.collisions if shape.link == "panda_leftfinger")
    rng = np.random.default_rng(1)
    for polytope in (shape_polytope(finger), box_polytope(np.array([0.1, 0.05, 0.085]))):
        spheres = cover_with_spheres(polytope, 0.012)
        assert covering_slack(spheres, sample_polytope(polytope, 1500, rng)) >= -1e-9
        planes = polytope.planes()
        reaches = [overshoot(c, r, planes) for c, r in zip(spheres.centers, spheres.radii, strict=True)]
        assert max(reaches) < 0.03


def test_batch_kinematics_is_pybullets(kitchen: KitchenScene, free: SpherePair) -> None:
    tree, body = free.model.model.tree, kitchen.robot.body
    qs = np.random.default_rng(1).uniform(free.model.lower, free.model.upper, size=(12, 7))
    poses = tree.link_poses(qs)
    with kitchen.scene.preserved():
        for q, pose in zip(qs, poses, strict=True):
            kitchen.robot.set_configuration(q)
            for link in ("panda_link3", "panda_link7", "panda_hand", "panda_leftfinger", "panda_rightfinger"):
                expected = body.link_pose(link).matrix()
                np.testing.assert_allclose(pose[tree.link_index[link]], expected, atol=1e-6)


def near_contact(pair: SpherePair, count: int, rng: np.random.Generator) -> np.ndarray:
    """Configurations within a few millimetres of PyBullet's contact: bisected between a free and a
    colliding sample."""
    lower, upper = pair.pybullet.lower, pair.pybullet.upper
    qs = rng.uniform(lower, upper, size=(4 * count, 7))
    valid = pair.pybullet.is_valid(qs)
    free, colliding = qs[valid][:count], qs[~valid][:count]
    count = min(len(free), len(colliding))
    free, colliding = free[:count], colliding[:count]
    for _ in range(12):
        middle = (free + colliding) / 2.0
        middle_valid = pair.pybullet.is_valid(middle)
        free = np.where(middle_valid[:, None], middle, free)
        colliding = np.where(middle_valid[:, None], colliding, middle)
    return np.concatenate([free, colliding])


@pytest.mark.parametrize("scene", ["free", "holding"])
def test_never_calls_free_what_pybullet_finds_colliding(request: pytest.FixtureRequest, scene: str) -> None:
    pair: SpherePair = request.getfixturevalue(scene)
    rng = np.random.default_rng(2)
    random = rng.uniform(pair.pybullet.lower, pair.pybullet.upper, size=(RANDOM_CONFIGURATIONS, 7))
    for qs in (random, near_contact(pair, NEAR_CONFIGURATIONS, rng)):
        pybullet, spheres = pair.pybullet.is_valid(qs), pair.model.is_valid(qs)
        assert 0.05 < pybullet.mean() < 0.95
        missed = np.flatnonzero(spheres & ~pybullet)
        assert len(missed) == 0, pair.pybullet.min_clearance(qs[missed])
    pybullet, spheres = pair.pybullet.is_valid(random), pair.model.is_valid(random)
    false_positives = np.count_nonzero(pybullet & ~spheres) / np.count_nonzero(pybullet)
    assert false_positives < 0.06  # tight: few configurations PyBullet finds free are refused


@pytest.mark.slow
def test_compiled_kernel_agrees_with_numpy(free: SpherePair, holding: SpherePair) -> None:
    rng = np.random.default_rng(3)
    for pair in (free, holding):
        qs = rng.uniform(pair.model.lower - 0.05, pair.model.upper + 0.05, size=(300, 7))
        verdicts = pair.model.is_valid(qs)
        assert 0.05 < verdicts.mean() < 0.95
        assert verdicts.tolist() == pair.model.is_valid_uncompiled(qs).tolist()


def test_pair_gradients_are_the_finite_differences(free: SpherePair, holding: SpherePair) -> None:
    rng = np.random.default_rng(4)
    step = 1e-6
    for pair in (free, holding):
        for q in rng.uniform(pair.model.lower, pair.model.upper, size=(5, 7)):
            distances, gradients = pair.model.pair_distances(q)
            numeric = np.empty_like(gradients)
            for joint in range(7):
                offset = np.zeros(7)
                offset[joint] = step
                numeric[:, joint] = (
                    pair.model.pair_distances(q + offset)[0] - pair.model.pair_distances(q - offset)[0]
                ) / (2 * step)
            # pairs at a kink (a box edge, a sphere centre on a box's medial plane) move off it
            smooth = np.all(np.abs(numeric - gradients) < 1e-4, axis=1)
            assert smooth.mean() > 0.99
            assert np.all(np.abs(distances[:3]) < 10.0)
            signed, _ = pair.model.signed_distance(q)
            assert signed == pytest.approx(min(float(distances.min()), pair.model.distance_horizon))


def test_model_is_built_from_what_the_simulator_loaded(kitchen: KitchenScene) -> None:
    """Drift: every obstacle box sits where PyBullet has that link's collision shapes, the drawer's
    boxes follow its joint, and the robot stands where PyBullet's does."""
    with kitchen.scene.preserved():
        for opening in (0.0, 0.2):
            kitchen.scene.set_joint_positions(kitchen.kitchen, ["drawer_joint"], [opening])
            spheres = twin(kitchen.collision_checker(), SphereCollisionChecker).model
            boxes = spheres.boxes
            corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
            for body_name, link in set(boxes.owners):
                owned = [i for i, owner in enumerate(boxes.owners) if owner == (body_name, link)]
                points = np.concatenate(
                    [
                        (corners * boxes.half_extents[i]) @ boxes.rotations[i].T + boxes.centers[i]
                        for i in owned
                    ]
                )
                body = kitchen.scene.body(body_name)
                low, high = p.getAABB(body.uid, body.link_index(link), physicsClientId=body.client)
                np.testing.assert_allclose(points.min(axis=0), low, atol=2e-3, err_msg=f"{body_name}/{link}")
                np.testing.assert_allclose(points.max(axis=0), high, atol=2e-3, err_msg=f"{body_name}/{link}")
            pose = spheres.tree.link_poses(kitchen.robot.configuration()[None])[0]
            np.testing.assert_allclose(pose[0], kitchen.robot.body.base_pose().matrix(), atol=1e-9)


def test_screened_checker_gives_drakes_verdicts(free: SpherePair, kitchen: KitchenScene) -> None:
    description = describe_collision_checker(free.pybullet)
    drake = DrakeCollisionChecker(description)
    screened = SphereScreenedChecker(free.model, drake)
    qs = np.random.default_rng(5).uniform(drake.lower, drake.upper, size=(200, 7))
    assert screened.is_valid(qs).tolist() == drake.is_valid(qs).tolist()
