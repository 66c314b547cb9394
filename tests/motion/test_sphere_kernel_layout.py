"""The validity kernel's fast paths change no verdict: its branch-free sines and cosines are libm's
to an ulp, its folded kinematic tree puts every sphere where the full tree does, and its verdicts
are the numpy reference's on configurations within a hair of the spheres' own contact."""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.codes import FIXED, PRISMATIC, REVOLUTE, REVOLUTE_Z, SKIPPED
from kitchen_tamp.motion.geometry.spheres.kernels.layout import kernel_arguments
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import (
    folded_link_poses,
    joint_sines_cosines,
    place_point,
)
from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import origin_axes
from tests.motion import test_sphere_pair_tables
from tests.motion.poses import rotation

SINES_COSINES: Any = joint_sines_cosines
FOLDED_POSES: Any = folded_link_poses
PLACE: Any = place_point

checkers = test_sphere_pair_tables.checkers
"""The fixture: the free hand, and the hand holding spam as the pick skill grasped it."""


def test_sines_and_cosines_are_numpys_to_an_ulp() -> None:
    qs = np.random.default_rng(30).uniform(-4.0, 4.0, size=(20000, 7))
    qs[:8, 0] = [0.0, np.pi / 4, np.pi / 2, -np.pi / 2, np.pi, -np.pi, 3 * np.pi / 4, 1e-300]
    sines, cosines = np.empty_like(qs), np.empty_like(qs)
    for m in range(len(qs)):
        SINES_COSINES(qs, m, sines[m], cosines[m])
    assert np.max(np.abs(sines - np.sin(qs))) < 3e-16
    assert np.max(np.abs(cosines - np.cos(qs))) < 3e-16


def test_every_joint_kind_of_the_folded_kinematics_is_the_matrix_product() -> None:
    """A chain with a revolute joint about a tilted axis, one about z, a prismatic joint and a
    skipped link: each kept pose is its parent's times its origin times its joint's motion."""
    rng = np.random.default_rng(33)
    kinds = np.array([FIXED, REVOLUTE, REVOLUTE_Z, SKIPPED, PRISMATIC], dtype=np.int64)
    parents = np.array([-1, 0, 1, 2, 2], dtype=np.int64)
    variables = np.array([-1, 0, 1, -1, 2], dtype=np.int64)
    axes = np.array([[0, 0, 0], [0.6, 0.0, 0.8], [0, 0, 1], [0, 0, 0], [0.0, 0.6, -0.8]], dtype=float)
    origins = np.stack(
        [rotation(a / np.linalg.norm(a), rng.uniform(-3, 3)) for a in rng.normal(size=(5, 3))]
    )
    origins[:, :3, 3] = rng.normal(size=(5, 3))
    root = origins[0].copy()
    qs = rng.uniform(-3.0, 3.0, size=(20, 3))
    poses, frame = np.full((5, 3, 4), np.nan), np.empty((3, 4))
    sines, cosines = np.empty(3), np.empty(3)
    no_quarter_turns = origin_axes(origins, kinds)
    assert not no_quarter_turns.any()  # these origins turn by arbitrary angles
    for m in range(len(qs)):
        chain = (root, parents, origins, kinds, axes, variables, no_quarter_turns)
        FOLDED_POSES(qs, m, *chain, poses, frame, sines, cosines)
        expected = [root]
        expected.append(expected[0] @ origins[1] @ rotation(axes[1], qs[m, 0]))
        expected.append(expected[1] @ origins[2] @ rotation(axes[2], qs[m, 1]))
        slide = np.eye(4)
        slide[:3, 3] = axes[4] * qs[m, 2]
        expected.extend([expected[2], expected[2] @ origins[4] @ slide])
        for link in (0, 1, 2, 4):
            assert np.allclose(poses[link], expected[link][:3], atol=1e-12)
        assert np.all(np.isnan(poses[3]))


def test_a_joint_about_z_behind_quarter_turns_is_the_matrix_product() -> None:
    """Every signed permutation of the axes as the origin of a joint about z (with URDF's rounding
    of a half pi in its zeros): the quarter-turn path gives the matrix product's pose."""
    rng = np.random.default_rng(34)
    kinds = np.array([FIXED, REVOLUTE_Z], dtype=np.int64)
    parents, variables = np.array([-1, 0], dtype=np.int64), np.array([-1, 0], dtype=np.int64)
    axes = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    root = rotation(np.array([0.0, 0.6, 0.8]), 0.7)
    root[:3, 3] = [0.1, -0.2, 0.3]
    poses, frame, sines, cosines = np.empty((2, 3, 4)), np.empty((3, 4)), np.empty(1), np.empty(1)
    for permutation in itertools.permutations(range(3)):
        for signs in itertools.product((-1.0, 1.0), repeat=3):
            origins = np.stack([np.eye(4), np.eye(4)])
            origins[1, :3, :3] = 6e-17  # what rpy of a half pi leaves in the zeros
            origins[1, list(permutation), [0, 1, 2]] = signs
            origins[1, :3, 3] = rng.normal(size=3)
            quarter_turns = origin_axes(origins, kinds)
            assert quarter_turns[1, 0] != 0
            for q in rng.uniform(-3.0, 3.0, size=(5, 1)):
                FOLDED_POSES(q[None], 0, root, parents, origins, kinds, axes, variables, quarter_turns,
                             poses, frame, sines, cosines)
                expected = root @ origins[1] @ rotation(axes[1], q[0])
                assert np.allclose(poses[1], expected[:3], atol=1e-12)


def test_folded_tree_places_every_sphere_where_the_full_tree_does(
    checkers: list[SphereCollisionChecker],
) -> None:
    rng = np.random.default_rng(31)
    for checker in checkers:
        model = checker.model
        arguments = kernel_arguments(model, checker.lower, checker.upper)
        root, parents, origins, kinds, axes, variables = arguments[2:8]
        sphere_links, sphere_centers = arguments[13], arguments[14]
        quarter_turns = origin_axes(origins, kinds)
        assert np.count_nonzero(quarter_turns[:, 0]) == 7  # every joint of the Panda
        qs = rng.uniform(checker.lower, checker.upper, size=(50, 7))
        expected = model.sphere_positions(model.tree.link_poses(qs))
        poses, frame = np.empty((len(parents), 3, 4)), np.empty((3, 4))
        sines, cosines = np.empty(7), np.empty(7)
        world = np.empty_like(sphere_centers)
        for m in range(len(qs)):
            chain = (root, parents, origins, kinds, axes, variables, quarter_turns)
            FOLDED_POSES(qs, m, *chain, poses, frame, sines, cosines)
            for s in range(len(sphere_links)):
                PLACE(poses, sphere_links[s], sphere_centers, s, world)
            # Within 1e-10 m: the quarter turns read pybullet's 4.9e-12 (rpy 1.57079632679) as 0.
            assert np.max(np.abs(world - expected[m])) < 1e-10


@pytest.mark.slow
def test_verdicts_at_the_spheres_own_contact_are_the_numpy_references(
    checkers: list[SphereCollisionChecker],
) -> None:
    """Configurations bisected to within 1e-8 rad of where the spheres start to touch (where a
    reordered or rounded check would first disagree; uniform ones are compared in test_sphere_model)."""
    rng = np.random.default_rng(32)
    for checker in checkers:
        qs = rng.uniform(checker.lower, checker.upper, size=(4000, 7))
        valid = checker.is_valid(qs)
        free, colliding = qs[valid][:60], qs[~valid][:60]
        count = min(len(free), len(colliding))
        free, colliding = free[:count], colliding[:count]
        for _ in range(28):
            middle = (free + colliding) / 2.0
            middle_valid = checker.is_valid(middle)[:, None]
            free, colliding = np.where(middle_valid, middle, free), np.where(middle_valid, colliding, middle)
        near = np.concatenate([free, colliding])
        assert checker.is_valid(near).tolist() == checker.is_valid_uncompiled(near).tolist()
