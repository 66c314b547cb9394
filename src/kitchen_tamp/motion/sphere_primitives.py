"""Compiled primitives that the sphere model's kernels share: forward kinematics of a link
chain and the distances of a point or sphere to a box, a bound or another point.

Used by the validity kernel (`sphere_kernels`) and the clearance kernel (`clearance_kernel`);
numba inlines them into each, and caches them on disk like the kernels (``cache=True``).
Link layout as in `sphere_kernels`: ``parents``, ``origins``, ``kinds`` (FIXED, REVOLUTE,
PRISMATIC), ``axes`` and ``variables``.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

FIXED, REVOLUTE, PRISMATIC = 0, 1, 2


@numba.njit(cache=True, fastmath=True, inline="always")
def compose(a: FloatArray, b: FloatArray, out: FloatArray) -> None:
    """out = a @ b for rigid 4x4 transforms (numba's @ needs BLAS from scipy)."""
    for i in range(3):
        for j in range(4):
            out[i, j] = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j]
        out[i, 3] += a[i, 3]
    out[3, 0] = out[3, 1] = out[3, 2] = 0.0
    out[3, 3] = 1.0


@numba.njit(cache=True, fastmath=True, inline="always")
def link_poses(
    q: FloatArray,
    root: FloatArray,
    parents: npt.NDArray[np.int64],
    origins: FloatArray,
    kinds: npt.NDArray[np.int64],
    axes: FloatArray,
    variables: npt.NDArray[np.int64],
    poses: FloatArray,
    motion: FloatArray,
    frame: FloatArray,
) -> None:
    for link in range(parents.shape[0]):
        if parents[link] < 0:
            poses[link] = root
            continue
        kind = kinds[link]
        if kind == FIXED:
            compose(poses[parents[link]], origins[link], poses[link])
            continue
        compose(poses[parents[link]], origins[link], frame)
        angle = q[variables[link]]
        x, y, z = axes[link, 0], axes[link, 1], axes[link, 2]
        motion[:] = 0.0
        motion[3, 3] = 1.0
        if kind == REVOLUTE:
            c, s = np.cos(angle), np.sin(angle)
            t = 1.0 - c
            motion[0, 0], motion[0, 1], motion[0, 2] = t * x * x + c, t * x * y - s * z, t * x * z + s * y
            motion[1, 0], motion[1, 1], motion[1, 2] = t * x * y + s * z, t * y * y + c, t * y * z - s * x
            motion[2, 0], motion[2, 1], motion[2, 2] = t * x * z - s * y, t * y * z + s * x, t * z * z + c
        else:
            motion[0, 0] = motion[1, 1] = motion[2, 2] = 1.0
            motion[0, 3], motion[1, 3], motion[2, 3] = angle * x, angle * y, angle * z
        compose(frame, motion, poses[link])


@numba.njit(cache=True, fastmath=True, inline="always")
def box_gap(point: FloatArray, rotation: FloatArray, center: FloatArray, half: FloatArray) -> float:
    """Signed distance from a point to an oriented box (negative inside)."""
    outside = 0.0
    deepest = -1e300
    for axis in range(3):
        local = 0.0
        for k in range(3):
            local += rotation[k, axis] * (point[k] - center[k])
        excess = abs(local) - half[axis]
        if excess > 0.0:
            outside += excess * excess
        if excess > deepest:
            deepest = excess
    if outside > 0.0:
        return float(np.sqrt(outside))
    return float(deepest)


@numba.njit(cache=True, fastmath=True, inline="always")
def aabb_gap(point: FloatArray, low: FloatArray, high: FloatArray) -> float:
    """Distance from a point to an axis-aligned box (zero inside): a lower bound of the gap to any
    shape inside the box."""
    total = 0.0
    for k in range(3):
        excess = max(low[k] - point[k], point[k] - high[k], 0.0)
        total += excess * excess
    return float(np.sqrt(total))


@numba.njit(cache=True, fastmath=True, inline="always")
def distance(a: FloatArray, b: FloatArray) -> float:
    dx, dy, dz = a[0] - b[0], a[1] - b[1], a[2] - b[2]
    return float(np.sqrt(dx * dx + dy * dy + dz * dz))


@numba.njit(cache=True, fastmath=True, inline="always")
def apart(a: FloatArray, b: FloatArray, reach: float) -> bool:
    """Whether the points are at least ``reach`` apart (squared distances: no root)."""
    if reach <= 0.0:
        return True
    dx, dy, dz = a[0] - b[0], a[1] - b[1], a[2] - b[2]
    return bool(dx * dx + dy * dy + dz * dz >= reach * reach)


@numba.njit(cache=True, fastmath=True, inline="always")
def world_point(pose: FloatArray, local: FloatArray, out: FloatArray) -> None:
    for k in range(3):
        out[k] = pose[k, 0] * local[0] + pose[k, 1] * local[1] + pose[k, 2] * local[2] + pose[k, 3]
