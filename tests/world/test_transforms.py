from __future__ import annotations

import numpy as np

from kitchen_tamp.world import Pose, rotation_about_axis
from kitchen_tamp.world.transforms import matrix_to_quaternion, quaternion_to_matrix


def random_pose(rng: np.random.Generator) -> Pose:
    q = rng.normal(size=4)
    return Pose.from_parts(rng.uniform(-1, 1, 3), q / np.linalg.norm(q))


def test_compose_with_inverse_is_identity() -> None:
    rng = np.random.default_rng(0)
    for _ in range(20):
        world_from_a = random_pose(rng)
        identity = world_from_a @ world_from_a.inverse()
        assert np.allclose(identity.matrix(), np.eye(4), atol=1e-9)


def test_frame_algebra_maps_points_like_matrices() -> None:
    rng = np.random.default_rng(1)
    world_from_hand, hand_from_box = random_pose(rng), random_pose(rng)
    point = rng.uniform(-1, 1, 3)
    world_from_box = world_from_hand @ hand_from_box
    assert np.allclose(world_from_box.apply(point), world_from_hand.apply(hand_from_box.apply(point)))


def test_quaternion_matrix_round_trip() -> None:
    rng = np.random.default_rng(2)
    for _ in range(50):
        rotation = rotation_about_axis(rng.normal(size=3), rng.uniform(-np.pi, np.pi))
        assert np.allclose(quaternion_to_matrix(matrix_to_quaternion(rotation)), rotation, atol=1e-9)


def test_distance_to_measures_position_and_angle() -> None:
    a = Pose()
    b = Pose.from_rotation((0.3, 0.4, 0.0), rotation_about_axis((0.0, 0.0, 1.0), 0.5))
    position_error, angle_error = a.distance_to(b)
    assert np.isclose(position_error, 0.5)
    assert np.isclose(angle_error, 0.5)
