"""The fast checker (per-link pairs behind an AABB broadphase, raw state save/restore) answers
exactly what a straightforward whole-body ``getClosestPoints`` checker answers."""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import pybullet as p
import pytest

from kitchen_tamp.world import (
    BASE_LINK,
    AllowedContact,
    Body,
    Pose,
    PyBulletCollisionChecker,
    Robot,
    Scene,
    SceneState,
    make_collision_checker,
)
from tests.world.conftest import sugar_riding_in_drawer

CONFIGURATIONS = 250


def _ancestry(body: Body, link: int) -> list[tuple[int, bool]]:
    parents = {j.index: (j.parent_index, j.movable) for j in body.joints}
    chain = []
    while link != BASE_LINK:
        parent, movable = parents[link]
        chain.append((link, movable))
        link = parent
    return chain


def _allowance(allowed: Sequence[AllowedContact], robot_link: str, body: str, link: str) -> float:
    return max((a.max_penetration for a in allowed if a.allows(robot_link, body, link)), default=0.0)


def _carried_allowance(allowed: Sequence[AllowedContact], carried: str, body: str, link: str) -> float:
    return max((a.max_penetration for a in allowed if a.allows_carried(carried, body, link)), default=0.0)


def _reference_distances(
    scene: Scene, robot: Robot, allowed: Sequence[AllowedContact], horizon: float
) -> list[tuple[float, float]]:
    """(distance, allowance) of every checked pair at the current state, one whole-body
    query at a time."""
    body, client = robot.body, robot.body.client
    carried = [a for a in scene.attachments if a.parent is body]
    obstacles = [b for b in scene.bodies if b is not body and all(b is not a.child for a in carried)]
    first_arm_link = body.joint(robot.description.arm_joints[0]).index
    moving = {i for i in body.link_indices if any(lnk == first_arm_link for lnk, _ in _ancestry(body, i))}
    distances = []
    for obstacle in obstacles:
        for pt in p.getClosestPoints(body.uid, obstacle.uid, horizon, physicsClientId=client):
            names = (body.link_name(pt[3]), obstacle.name, obstacle.link_name(pt[4]))
            if pt[3] in moving:
                distances.append((pt[8], _allowance(allowed, *names)))
    for attachment in carried:
        child = attachment.child
        for other in obstacles:
            distances += [
                (pt[8], _carried_allowance(allowed, child.name, other.name, other.link_name(pt[4])))
                for pt in p.getClosestPoints(child.uid, other.uid, horizon, physicsClientId=client)
            ]
        for pt in p.getClosestPoints(child.uid, body.uid, horizon, physicsClientId=client):
            names = (body.link_name(pt[4]), child.name, child.link_name(pt[3]))
            distances.append((pt[8], _allowance(allowed, *names)))
    shaped = [i for i in body.link_indices if p.getCollisionShapeData(body.uid, i, physicsClientId=client)]
    for a, b in itertools.combinations(shaped, 2):
        chain_a, chain_b = _ancestry(body, a), _ancestry(body, b)
        shared = {lnk for lnk, _ in chain_a} & {lnk for lnk, _ in chain_b}
        if sum(m for lnk, m in chain_a + chain_b if lnk not in shared) >= 2:
            distances += [
                (pt[8], 0.0)
                for pt in p.getClosestPoints(body.uid, body.uid, horizon, a, b, physicsClientId=client)
            ]
    return distances


def _reference(
    scene: Scene, robot: Robot, q: np.ndarray, allowed: Sequence[AllowedContact], margin: float
) -> tuple[bool, float]:
    """(valid, min clearance capped at 0.5) at ``q``, the scene put back afterwards."""
    with scene.preserved():
        robot.set_configuration(q)
        near = _reference_distances(scene, robot, allowed, max(margin, 0.0))
        valid = robot.within_limits(q) and all(d >= (-a if a > 0.0 else margin) for d, a in near)
        measured = _reference_distances(scene, robot, allowed, 0.5)
        clearance = min([d + a for d, a in measured if a == 0.0 or d + a < 0.0], default=0.5)
    return valid, clearance


def assert_same_state(found: SceneState, expected: SceneState) -> None:
    """The checker left the scene as it found it (orientations to within an ulp or so)."""
    assert found.joint_positions == expected.joint_positions
    assert found.attachments == expected.attachments
    for (name, pose), (expected_name, expected_pose) in zip(
        found.base_poses, expected.base_poses, strict=True
    ):
        assert name == expected_name
        assert max(pose.distance_to(expected_pose)) < 1e-9


def _random_configurations(robot: Robot, count: int, seed: int) -> np.ndarray:
    """Uniform in the limits, a few just outside them."""
    rng = np.random.default_rng(seed)
    qs = rng.uniform(robot.lower, robot.upper, size=(count, robot.dof))
    qs[::50, 3] = robot.upper[3] + 0.01
    return qs


def _assert_agrees(
    scene: Scene,
    robot: Robot,
    checker: PyBulletCollisionChecker,
    qs: np.ndarray,
    allowed: Sequence[AllowedContact],
) -> None:
    before = scene.save_state()
    fast_valid = checker.is_valid(qs)
    fast_clearance = checker.min_clearance(qs[:20])
    assert_same_state(scene.save_state(), before)
    expected = [_reference(scene, robot, q, allowed, checker.margin) for q in qs]
    assert fast_valid.tolist() == [valid for valid, _ in expected]
    # Distances agree to GJK's tolerance (a carried box is placed by a different float path).
    assert np.allclose(fast_clearance, [clearance for _, clearance in expected[:20]], rtol=0.0, atol=1e-6)
    assert 0 < fast_valid.sum() < len(qs)
    for q, valid in zip(qs[:40], fast_valid[:40], strict=True):
        assert checker.in_collision(q) == (not valid)


def _hold_sugar(scene: Scene, robot: Robot) -> Body:
    """Attach the sugar box just below the fingertips."""
    box = scene.body("sugar")
    robot.set_configuration(robot.mid_configuration())
    box.reset_base_pose(robot.tool_pose().translated((0.0, 0.0, -0.12)))
    scene.attach(box, robot.body, robot.description.hand_link)
    return box


def test_agrees_with_reference_free_arm(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    checker = make_collision_checker(scene, robot)
    _assert_agrees(scene, robot, checker, _random_configurations(robot, CONFIGURATIONS, 0), ())


def test_agrees_with_reference_holding_a_box(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    _hold_sugar(scene, robot)
    checker = make_collision_checker(scene, robot)
    assert checker.carried
    _assert_agrees(scene, robot, checker, _random_configurations(robot, CONFIGURATIONS, 1), ())


@pytest.mark.parametrize("margin", [0.002, -0.005])
def test_agrees_with_reference_with_margin_and_allowed_contact(
    panda_scene: tuple[Scene, Robot], margin: float
) -> None:
    scene, robot = panda_scene
    kitchen = scene.body("kitchen")
    scene.set_joint_positions(kitchen, ["drawer_joint"], [kitchen.joint("drawer_joint").upper])
    allowed = [AllowedContact("kitchen", "drawer_handle", robot.gripper_links), AllowedContact("sugar")]
    checker = make_collision_checker(scene, robot, allowed, margin=margin)
    _assert_agrees(scene, robot, checker, _random_configurations(robot, 100, 2), allowed)


def test_checker_keeps_its_snapshot_when_the_scene_changes(panda_scene: tuple[Scene, Robot]) -> None:
    """Made while holding the box; asked after the box was let go and the arm moved."""
    scene, robot = panda_scene
    box = _hold_sugar(scene, robot)
    checker = make_collision_checker(scene, robot)
    qs = _random_configurations(robot, 60, 3)
    expected = checker.is_valid(qs)
    scene.detach(box)
    scene.set_base_pose(box, Pose((2.0, 2.0, 2.0)))
    robot.set_configuration(robot.lower + 0.1)
    before = scene.save_state()
    assert checker.is_valid(qs).tolist() == expected.tolist()
    assert_same_state(scene.save_state(), before)


def test_along_agrees_with_reference(panda_scene: tuple[Scene, Robot]) -> None:
    """The drawer slides with each configuration; a box attached to the drawer rides along."""
    scene, robot = panda_scene
    kitchen = sugar_riding_in_drawer(scene)
    checker = make_collision_checker(scene, robot)
    joint = kitchen.joint("drawer_joint")
    qs = _random_configurations(robot, 60, 4)
    openings = np.linspace(joint.lower, joint.upper, len(qs))
    valid = checker.is_valid_along(qs, kitchen, ["drawer_joint"], openings)
    clearance = checker.min_clearance_along(qs[:10], kitchen, ["drawer_joint"], openings[:10])
    for i, q in enumerate(qs):
        with scene.preserved():
            scene.set_joint_positions(kitchen, ["drawer_joint"], [openings[i]])
            expected_valid, expected_clearance = _reference(scene, robot, q, (), 0.0)
        assert valid[i] == expected_valid
        if i < 10:
            assert abs(clearance[i] - expected_clearance) < 1e-6



def test_checkers_of_the_same_scene_share_one_pair_table(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    first, second = make_collision_checker(scene, robot), make_collision_checker(scene, robot)
    assert first._checked is second._checked
    touching = [AllowedContact("sugar", max_penetration=0.002)]
    allowing = make_collision_checker(scene, robot, touching)
    assert allowing._checked is not first._checked
    assert allowing._checked is make_collision_checker(scene, robot, touching)._checked
    box = _hold_sugar(scene, robot)
    holding = make_collision_checker(scene, robot)
    assert holding.carried and holding._checked is not first._checked
    _assert_agrees(scene, robot, holding, _random_configurations(robot, 100, 4), ())
    scene.detach(box)
    again = make_collision_checker(scene, robot, touching)
    assert again._checked is allowing._checked  # the sugar, now loose, is an obstacle again
    _assert_agrees(scene, robot, again, _random_configurations(robot, 100, 5), touching)
