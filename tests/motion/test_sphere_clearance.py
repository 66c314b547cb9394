"""The sphere model's smooth clearance (the compiled kernel trajectory optimisation uses): its value
is the summed hinge of every pair's numpy distance, its gradient is the finite-difference one, and
a value at or above the margin means every pair keeps the margin."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene, sample_targets
from kitchen_tamp.motion.geometry.spheres.clearance import HINGE_AT_FLOOR, SphereClearance
from kitchen_tamp.motion.geometry.spheres.distances import pair_distances
from kitchen_tamp.motion.geometry.spheres.scene import SphereScene
from kitchen_tamp.world.scene_description import describe_collision_checker

MARGIN, WIDTH = 0.005, 0.01


@pytest.fixture(scope="module")
def scenes(kitchen: KitchenScene) -> dict[str, SphereScene]:
    """The arm alone, and holding the spam box as the pick skill grasped it."""
    free = SphereScene(describe_collision_checker(kitchen.collision_checker()))
    with kitchen.scene.preserved():
        sample_targets(kitchen, "pickUp", ("spam", "countertop"), np.random.default_rng(0)).apply(kitchen)
        holding = SphereScene(describe_collision_checker(kitchen.collision_checker()))
    return {"free": free, "holding": holding}


def _near_contact(clearance: SphereClearance, rng: np.random.Generator, count: int) -> np.ndarray:
    """Configurations with some pair within the influence width (where the penalty is not zero)."""
    qs = rng.uniform(clearance.model.arm_lower, clearance.model.arm_upper, size=(20 * count, 7))
    values, _ = clearance(qs)
    near = qs[(values < MARGIN + WIDTH) & (values > MARGIN - 2 * WIDTH)]
    assert len(near) >= count
    return near[:count]


@pytest.mark.parametrize("held", ["free", "holding"])
def test_value_is_the_hinge_sum_of_every_pairs_distance(scenes: dict[str, SphereScene], held: str) -> None:
    clearance = SphereClearance(scenes[held], MARGIN, WIDTH)
    model = clearance.model
    qs = np.random.default_rng(1).uniform(model.arm_lower, model.arm_upper, size=(200, 7))
    values, gradients = clearance(qs)
    assert values.shape == (200,) and gradients.shape == (200, 7)
    x = (pair_distances(clearance.model, clearance.pairs, qs) - MARGIN - WIDTH) / WIDTH
    negative = np.minimum(x, -1e-12)
    hinge = np.where(x < 0.0, -negative * np.exp(1.0 / negative), 0.0)
    expected = MARGIN + WIDTH - WIDTH / HINGE_AT_FLOOR * hinge.sum(axis=1)
    np.testing.assert_allclose(values, expected, rtol=0, atol=1e-9)
    assert clearance.evaluations == 200


@pytest.mark.parametrize("held", ["free", "holding"])
def test_gradients_are_the_finite_differences(scenes: dict[str, SphereScene], held: str) -> None:
    clearance = SphereClearance(scenes[held], MARGIN, WIDTH)
    qs = _near_contact(clearance, np.random.default_rng(2), 40)
    _, gradients = clearance(qs)
    step = 1e-6
    numeric = np.empty_like(gradients)
    for joint in range(7):
        offset = np.zeros(7)
        offset[joint] = step
        numeric[:, joint] = (clearance(qs + offset)[0] - clearance(qs - offset)[0]) / (2 * step)
    assert np.abs(gradients).max() > 1e-3  # near contact: the gradients are not all zero
    # a pair at a box edge or a sphere centre on a box's medial plane is not differentiable
    smooth = np.all(np.abs(numeric - gradients) <= 1e-5 + 1e-4 * np.abs(gradients), axis=1)
    assert smooth.mean() > 0.95


@pytest.mark.slow
def test_a_value_above_the_margin_keeps_every_pair_apart(scenes: dict[str, SphereScene]) -> None:
    clearance = SphereClearance(scenes["free"], MARGIN, WIDTH)
    model = clearance.model
    qs = np.random.default_rng(3).uniform(model.arm_lower, model.arm_upper, size=(2000, 7))
    values, _ = clearance(qs)
    closest = pair_distances(clearance.model, clearance.pairs, qs).min(axis=1)
    assert np.all(closest[values >= MARGIN] >= MARGIN)
    assert np.any(values >= MARGIN) and np.any(values < MARGIN)
    # and a pair closer than its floor always shows (one pair at x = -1 is the whole budget)
    assert np.all(values[closest < MARGIN] < MARGIN)


@pytest.mark.slow
def test_the_ends_of_a_move_have_the_full_clearance(scenes: dict[str, SphereScene]) -> None:
    model = scenes["holding"]
    plain = SphereClearance(model, MARGIN, WIDTH)
    qs = np.random.default_rng(5).uniform(model.arm_lower, model.arm_upper, size=(2000, 7))
    closest = pair_distances(model, plain.pairs, qs).min(axis=1)
    ends = qs[(closest < MARGIN) & (closest > 0.0)][:2]
    assert len(ends) == 2 and np.all(plain(ends)[0] < MARGIN)
    clearance = SphereClearance(model, MARGIN, WIDTH, ends=ends)
    values, gradients = clearance(ends)
    np.testing.assert_allclose(values, MARGIN + WIDTH)
    assert np.all(gradients == 0.0)
    distances = pair_distances(clearance.model, clearance.pairs, ends)
    lowered = clearance.floors < MARGIN
    assert lowered.any() and np.all(clearance.floors[~lowered] == MARGIN)
    # only pairs within the width of the margin at an end are lowered, by a width below their distance
    assert np.all(distances.min(axis=0)[lowered] < MARGIN + WIDTH)
    np.testing.assert_allclose(clearance.floors[lowered], distances.min(axis=0)[lowered] - WIDTH)
