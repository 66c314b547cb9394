"""Rigid poses for the motion tests' scenes and kinematic chains."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.motion.geometry.urdf import rpy_matrix


def pose(xyz: tuple[float, float, float], rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> np.ndarray:
    """The 4x4 pose at ``xyz`` turned by URDF's roll, pitch and yaw."""
    placed = np.eye(4)
    placed[:3, :3] = rpy_matrix(np.array(rpy))
    placed[:3, 3] = xyz
    return placed


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation (4x4) by ``angle`` about ``axis`` (any length)."""
    x, y, z = axis / np.linalg.norm(axis)
    cross = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    turned = np.eye(4)
    turned[:3, :3] += np.sin(angle) * cross + (1.0 - np.cos(angle)) * cross @ cross
    return turned
