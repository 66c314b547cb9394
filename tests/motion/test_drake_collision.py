"""The Drake collision model of the real kitchen answers like the PyBullet checker: same pairs,
the same verdict except within millimetres of contact, and a signed distance whose gradient is
the finite-difference one."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.trajopt.program import ClearanceConstraint, one_at_a_time
from kitchen_tamp.world import (
    AllowedContact,
    Pose,
    make_collision_checker,
)
from tests.motion.conftest import CheckerPair, free_hand_pair, holding_spam_pair, twin

CONFIGURATIONS = 500
NEAR_CONTACT = 0.003
"""Disagreements are allowed only where PyBullet's clearance is this close (m) to zero."""


DrakePair = CheckerPair[DrakeCollisionChecker]


@pytest.fixture(scope="module")
def free(kitchen: KitchenScene) -> DrakePair:
    return free_hand_pair(kitchen, DrakeCollisionChecker)


@pytest.fixture(scope="module")
def holding(kitchen: KitchenScene) -> DrakePair:
    return holding_spam_pair(kitchen, DrakeCollisionChecker)


def countertop_configurations(kitchen: KitchenScene) -> tuple[np.ndarray, np.ndarray]:
    """(free, colliding): IK for the tool 0.3 m above the countertop and inside the slab under it."""
    low, high = kitchen.kitchen.aabb("countertop")
    x, y = float((low[0] + high[0]) / 2.0), float((low[1] + high[1]) / 2.0)
    down = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])
    rng = np.random.default_rng(0)
    above = kitchen.ik.solve(Pose.from_rotation((x, y, float(high[2]) + 0.3), down), rng, [kitchen.home])
    inside = kitchen.ik.solve(Pose.from_rotation((x, y, float(high[2]) - 0.03), down), rng, [kitchen.home])
    assert above is not None and inside is not None
    return above, inside


@pytest.mark.parametrize("scene", ["free", "holding"])
def test_agrees_with_pybullet_except_near_contact(request: pytest.FixtureRequest, scene: str) -> None:
    pair: DrakePair = request.getfixturevalue(scene)
    rng = np.random.default_rng(1)
    qs = rng.uniform(pair.pybullet.lower, pair.pybullet.upper, size=(CONFIGURATIONS, 7))
    pybullet, drake = pair.pybullet.is_valid(qs), pair.model.is_valid(qs)
    assert 0.1 < pybullet.mean() < 0.95
    disagreements = np.flatnonzero(pybullet != drake)
    assert len(disagreements) <= 0.05 * CONFIGURATIONS
    clearance = pair.pybullet.min_clearance(qs[disagreements])
    distance = [pair.model.min_distance(q) for q in qs[disagreements]]
    report = [
        (int(i), bool(pybullet[i]), round(float(c), 5), round(d, 5))
        for i, c, d in zip(disagreements, clearance, distance, strict=True)
    ]
    assert np.all(np.abs(clearance) < NEAR_CONTACT), report
    assert np.all(np.abs(distance) < NEAR_CONTACT), report


@pytest.mark.parametrize("scene", ["free", "holding"])
def test_checks_the_same_pairs_as_pybullet(request: pytest.FixtureRequest, scene: str) -> None:
    pair: DrakePair = request.getfixturevalue(scene)
    pybullet = {  # white box: the PyBullet checker's pair table
        frozenset((f"{a.name}/{a.link_name(i)}", f"{b.name}/{b.link_name(j)}"))
        for a, i, b, j in pair.pybullet._pairs
    }
    assert pair.model.checked_pairs == pybullet


def test_allowed_contacts_are_checked_to_their_bound(kitchen: KitchenScene) -> None:
    handle = AllowedContact("kitchen", "drawer_handle", kitchen.robot.gripper_links)
    checker = make_collision_checker(kitchen.scene, kitchen.robot, [handle])
    drake = twin(checker, DrakeCollisionChecker)
    gripper_on_handle = frozenset(("panda/panda_hand", "kitchen/drawer_handle"))
    assert gripper_on_handle in drake.checked_pairs
    assert drake.contact_pairs == {gripper_on_handle: handle.max_penetration} | {
        frozenset((f"panda/{link}", "kitchen/drawer_handle")): handle.max_penetration
        for link in kitchen.robot.gripper_links
        if frozenset((f"panda/{link}", "kitchen/drawer_handle")) in drake.checked_pairs
    }
    assert frozenset(("panda/panda_link7", "kitchen/drawer_handle")) not in drake.contact_pairs


def test_hand_in_the_countertop_collides_in_both(kitchen: KitchenScene, free: DrakePair) -> None:
    above, inside = countertop_configurations(kitchen)
    for checker in (free.pybullet, free.model):
        assert checker.is_valid(np.stack([above, inside])).tolist() == [True, False]
        assert checker.segment_valid(above, above + 0.01)
        assert not checker.segment_valid(above, inside)
    assert free.model.min_distance(inside) < 0.0 < free.model.min_distance(above)
    assert not free.model.is_valid(free.model.upper + 0.1)[0]


def test_margin_means_minimum_distance(kitchen: KitchenScene, free: DrakePair) -> None:
    checker = make_collision_checker(kitchen.scene, kitchen.robot, margin=0.02)
    drake = twin(checker, DrakeCollisionChecker)
    qs = np.random.default_rng(2).uniform(drake.lower, drake.upper, size=(40, 7))
    distances = np.array([free.model.min_distance(q) for q in qs])
    assert drake.is_valid(qs).tolist() == (distances >= 0.02).tolist()


def test_signed_distance_gradient_is_the_finite_difference(free: DrakePair, holding: DrakePair) -> None:
    rng = np.random.default_rng(3)
    checked = 0
    for drake in (free.model, holding.model):
        for q in rng.uniform(drake.lower, drake.upper, size=(30, 7)):
            value, gradient = drake.signed_distance(q)
            if not 0.005 < value < drake.distance_horizon - 0.01:
                continue
            assert value == drake.min_distance(q)
            step = 1e-6
            finite = [
                (drake.signed_distance(q + step * e)[0] - drake.signed_distance(q - step * e)[0]) / (2 * step)
                for e in np.eye(7)
            ]
            assert np.allclose(gradient, finite, rtol=1e-4, atol=1e-6)
            checked += 1
    assert checked >= 10


def test_signed_distance_plugs_into_trajectory_optimisation(free: DrakePair) -> None:
    from pydrake.autodiffutils import ExtractGradient, ExtractValue, InitializeAutoDiff

    q = free.model.lower * 0.3 + free.model.upper * 0.7
    value, gradient = free.model.signed_distance(q)
    # one row: the waypoint q itself, out of a run of two waypoints
    constraint = ClearanceConstraint(one_at_a_time(free.model.signed_distance), np.array([[1.0, 0.0]]), [0])
    variables = InitializeAutoDiff(np.concatenate([q, np.zeros(7)])).reshape(-1)
    evaluated = constraint(variables)
    extracted: Any = (ExtractValue(evaluated), ExtractGradient(evaluated))
    assert float(np.ravel(extracted[0])[0]) == value
    assert np.allclose(np.ravel(extracted[1])[:7], gradient)
    assert np.all(np.ravel(extracted[1])[7:] == 0.0)
