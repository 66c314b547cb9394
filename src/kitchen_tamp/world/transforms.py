"""Rigid transforms: a frozen ``Pose`` with composition written as frame algebra.

``world_from_hand @ hand_from_box`` is ``world_from_box``. Quaternions are
(x, y, z, w), PyBullet's convention.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
Vector3 = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]

VectorLike = Sequence[float] | FloatArray

IDENTITY_QUATERNION: Quaternion = (0.0, 0.0, 0.0, 1.0)
UNIT_QUATERNION_TOLERANCE = 1e-6 + 1e-5
"""How far a pose's quaternion's norm may be from 1."""


def quaternion_to_matrix(quaternion: VectorLike) -> FloatArray:
    """3x3 rotation matrix of a unit quaternion (x, y, z, w)."""
    x, y, z, w = (float(v) for v in quaternion)
    norm = np.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def matrix_to_quaternion(rotation: FloatArray) -> Quaternion:
    """Unit quaternion (x, y, z, w) with w >= 0 of a 3x3 rotation matrix."""
    m = np.asarray(rotation, dtype=float)
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0.0:
        s = 2.0 * np.sqrt(trace + 1.0)
        q = np.array([(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4])
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * np.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = np.array([s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s])
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * np.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = np.array([(m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s])
    else:
        s = 2.0 * np.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = np.array([(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4, (m[1, 0] - m[0, 1]) / s])
    q /= np.linalg.norm(q)
    if q[3] < 0.0:
        q = -q
    return (float(q[0]), float(q[1]), float(q[2]), float(q[3]))


def rotation_about_axis(axis: VectorLike, angle: float) -> FloatArray:
    """3x3 rotation by ``angle`` radians about the unit vector ``axis`` (Rodrigues)."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    k = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.asarray(np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k))


@dataclass(frozen=True)
class Pose:
    """Position and orientation of one frame in another: ``a_from_b`` maps b-points to a."""

    position: Vector3 = (0.0, 0.0, 0.0)
    quaternion: Quaternion = IDENTITY_QUATERNION

    def __post_init__(self) -> None:
        if len(self.position) != 3 or len(self.quaternion) != 4:
            raise ValueError(f"a pose needs 3 coordinates and 4 quaternion entries, got {self}")
        # numpy's isclose on one scalar costs tens of microseconds, and poses are made by the
        # hundred thousand in a TAMP run: the same test (atol 1e-6, rtol 1e-5) in plain floats
        if abs(math.sqrt(sum(q * q for q in self.quaternion)) - 1.0) > UNIT_QUATERNION_TOLERANCE:
            raise ValueError(f"quaternion {self.quaternion} is not unit length")

    @staticmethod
    def from_parts(position: VectorLike, quaternion: VectorLike) -> Pose:
        """A pose from any sequences (e.g. PyBullet's tuples), normalising the quaternion."""
        q = np.asarray(quaternion, dtype=float)
        q = q / np.linalg.norm(q)
        return Pose(
            (float(position[0]), float(position[1]), float(position[2])),
            (float(q[0]), float(q[1]), float(q[2]), float(q[3])),
        )

    @staticmethod
    def from_rotation(position: VectorLike, rotation: FloatArray) -> Pose:
        """A pose from a position and a 3x3 rotation matrix."""
        return Pose.from_parts(position, matrix_to_quaternion(rotation))

    @staticmethod
    def from_matrix(matrix: FloatArray) -> Pose:
        """A pose from a 4x4 homogeneous matrix."""
        return Pose.from_rotation(matrix[:3, 3], matrix[:3, :3])

    @property
    def rotation(self) -> FloatArray:
        """The 3x3 rotation matrix (read-only: computed once per pose, as poses are immutable)."""
        rotation: FloatArray | None = self.__dict__.get("_rotation")
        if rotation is None:
            rotation = quaternion_to_matrix(self.quaternion)
            rotation.flags.writeable = False
            object.__setattr__(self, "_rotation", rotation)
        return rotation

    @property
    def translation(self) -> FloatArray:
        """The position as a numpy vector."""
        return np.array(self.position, dtype=float)

    def matrix(self) -> FloatArray:
        """The 4x4 homogeneous matrix."""
        m = np.eye(4)
        m[:3, :3] = self.rotation
        m[:3, 3] = self.position
        return m

    def __matmul__(self, other: Pose) -> Pose:
        return Pose.from_matrix(self.matrix() @ other.matrix())

    def inverse(self) -> Pose:
        """``b_from_a`` for ``a_from_b``."""
        r_t = self.rotation.T
        return Pose.from_rotation(-r_t @ self.translation, r_t)

    def apply(self, point: VectorLike) -> FloatArray:
        """Map a point given in the pose's child frame to its parent frame."""
        return np.asarray(self.rotation @ np.asarray(point, dtype=float) + self.translation)

    def translated(self, offset: VectorLike) -> Pose:
        """The same orientation, moved by ``offset`` expressed in the parent frame."""
        return Pose.from_parts(self.translation + np.asarray(offset, dtype=float), self.quaternion)

    def distance_to(self, other: Pose) -> tuple[float, float]:
        """(position error in metres, orientation error in radians) between two poses."""
        position_error = float(np.linalg.norm(self.translation - other.translation))
        dot = abs(float(np.dot(self.quaternion, other.quaternion)))
        angle_error = 2.0 * float(np.arccos(min(1.0, dot)))
        return position_error, angle_error


IDENTITY = Pose()
"""The identity transform."""
