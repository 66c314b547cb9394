"""Compiled primitives that the sphere model's kernels share: forward kinematics of a link
chain and the distances of a point or sphere to a box, a bound or another point.

The clearance kernel (`clearance_kernel`) uses the first group (4x4 poses, array rows, inlined by
numba); the validity kernel (`sphere_kernels`) the second (folded kinematics with 3x4 poses and
branch-free sines and cosines, arrays with row indices, inlined by LLVM, and `prefetch`). All are
cached on disk like the kernels (``cache=True``). Link layout as in `sphere_kernels`:
``parents``, ``origins``, ``kinds`` (FIXED, REVOLUTE, PRISMATIC; the folded layout also
REVOLUTE_Z and SKIPPED), ``axes`` and ``variables``.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numba
import numpy as np
import numpy.typing as npt
from llvmlite import ir  # type: ignore[import-untyped]
from numba.core import cgutils
from numba.extending import intrinsic

from kitchen_tamp.motion.geometry.spheres.kernels.codes import (
    FIXED,
    REVOLUTE,
    REVOLUTE_Z,
    SHAPE_CYLINDER,
    SHAPE_SPHERE,
    SKIPPED,
)

FloatArray = npt.NDArray[np.float64]



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
def world_point(pose: FloatArray, local: FloatArray, out: FloatArray) -> None:
    for k in range(3):
        out[k] = pose[k, 0] * local[0] + pose[k, 1] * local[1] + pose[k, 2] * local[2] + pose[k, 3]



# The functions below take arrays and row indices, never rows: a row taken from an array in a hot
# loop is a view whose reference count numba updates atomically, which costs more than the
# arithmetic around it.


# sin(r) = r + r z (s1 + z (s2 + ...)) and cos(r) = 1 - z/2 + z^2 (c1 + z (c2 + ...)), z = r^2: the
# Taylor series to degree 15 and 16. On [-pi/4, pi/4] the first terms left out are below 5e-17.
SINE_TERMS = tuple((-1.0) ** k / math.factorial(2 * k + 1) for k in range(1, 8))
COSINE_TERMS = tuple((-1.0) ** k / math.factorial(2 * k) for k in range(2, 9))
_PI = Fraction("3.14159265358979323846264338327950288419716939937510")
HALF_PI_HIGH = float(round(_PI / 2 * 2**32)) / 2**32
"""pi/2 to 33 bits, so that ``turns * HALF_PI_HIGH`` is exact for the joint ranges' few turns;
``HALF_PI_LOW`` is the rest."""
HALF_PI_LOW = float(_PI / 2 - Fraction(HALF_PI_HIGH))
TWO_OVER_PI = float(2 / _PI)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def sine_cosine(x: float) -> tuple[float, float]:
    """(sin x, cos x) to within an ulp of libm's, branch-free so that a loop of them runs in SIMD
    lanes instead of a libm call each (which cost more than the rest of the kinematics). Reduced
    by the nearest multiple of pi/2 (in two parts), then the Taylor polynomials above; within an
    ulp of numpy's over [-3.8, 3.8] (tested). Compiled with fastmath like its callers: LLVM inlines
    a function only into one with the same flags."""
    s1, s2, s3, s4, s5, s6, s7 = SINE_TERMS
    c1, c2, c3, c4, c5, c6, c7 = COSINE_TERMS
    turns = np.floor(x * TWO_OVER_PI + 0.5)
    r = (x - turns * HALF_PI_HIGH) - turns * HALF_PI_LOW
    z = r * r
    sine = r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * (s6 + z * s7))))))
    cosine = 1.0 - 0.5 * z + z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * (c6 + z * c7))))))
    quadrant = np.int64(turns) & 3
    swapped = (quadrant & 1) == 1
    a = cosine if swapped else sine
    b = sine if swapped else cosine
    return (-a if quadrant >= 2 else a), (-b if (quadrant == 1 or quadrant == 2) else b)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def joint_sines_cosines(qs: FloatArray, m: int, sines: FloatArray, cosines: FloatArray) -> None:
    """`sine_cosine` of every joint value of ``qs[m]``, in one pass of SIMD lanes."""
    for j in range(qs.shape[1]):
        sines[j], cosines[j] = sine_cosine(qs[m, j])


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _compose_into(poses: FloatArray, parent: int, origins: FloatArray, link: int, frame: FloatArray) -> None:
    """frame = poses[parent] @ origins[link] (top 3x4 rows)."""
    for i in range(3):
        a0, a1, a2 = poses[parent, i, 0], poses[parent, i, 1], poses[parent, i, 2]
        for j in range(3):
            frame[i, j] = a0 * origins[link, 0, j] + a1 * origins[link, 1, j] + a2 * origins[link, 2, j]
        frame[i, 3] = (
            a0 * origins[link, 0, 3]
            + a1 * origins[link, 1, 3]
            + a2 * origins[link, 2, 3]
            + poses[parent, i, 3]
        )


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _quarter_turn_z(
    poses: FloatArray,
    parent: int,
    origins: FloatArray,
    origin_axes: npt.NDArray[np.int64],
    link: int,
    c: float,
    s: float,
) -> None:
    """poses[link] = poses[parent] @ origins[link] @ (the turn of cosine ``c`` and sine ``s`` about
    z), the origin's rotation a signed permutation (``origin_axes[link]``: per column, its nonzero
    row plus one, signed as the entry)."""
    a0, a1, a2 = origin_axes[link, 0], origin_axes[link, 1], origin_axes[link, 2]
    r0, r1, r2 = abs(a0) - 1, abs(a1) - 1, abs(a2) - 1
    g0, g1, g2 = (1.0 if a0 > 0 else -1.0), (1.0 if a1 > 0 else -1.0), (1.0 if a2 > 0 else -1.0)
    t0, t1, t2 = origins[link, 0, 3], origins[link, 1, 3], origins[link, 2, 3]
    for i in range(3):
        f0, f1, f2 = g0 * poses[parent, i, r0], g1 * poses[parent, i, r1], g2 * poses[parent, i, r2]
        x, y, z = poses[parent, i, 0], poses[parent, i, 1], poses[parent, i, 2]
        poses[link, i, 3] = x * t0 + y * t1 + z * t2 + poses[parent, i, 3]
        poses[link, i, 0] = c * f0 + s * f1
        poses[link, i, 1] = c * f1 - s * f0
        poses[link, i, 2] = f2


@numba.njit(cache=True, fastmath=True, forceinline=True)
def folded_link_poses(
    qs: FloatArray,
    m: int,
    root: FloatArray,
    parents: npt.NDArray[np.int64],
    origins: FloatArray,
    kinds: npt.NDArray[np.int64],
    axes: FloatArray,
    variables: npt.NDArray[np.int64],
    origin_axes: npt.NDArray[np.int64],
    poses: FloatArray,
    frame: FloatArray,
    sines: FloatArray,
    cosines: FloatArray,
) -> None:
    """Top 3x4 rows of the world pose (``poses``, (L, 3, 4)) at configuration ``qs[m]`` of every
    link the folded layout keeps: the root, and each moving link from its kept parent and its
    origin (the fixed links between folded in); SKIPPED links are left as they are. ``sines`` and
    ``cosines`` (one per column of ``qs``) are scratch. A joint about z whose origin turns the axes
    by quarter turns (``origin_axes``, `validity_fields.origin_axes`) takes its parent's columns,
    permuted and signed, instead of multiplying by the origin's rotation: a third less time for
    the Panda's kinematics."""
    joint_sines_cosines(qs, m, sines, cosines)
    for link in range(parents.shape[0]):
        kind = kinds[link]
        if kind == SKIPPED:
            continue
        parent = parents[link]
        if parent < 0:
            for i in range(3):
                for j in range(4):
                    poses[link, i, j] = root[i, j]
            continue
        if kind == REVOLUTE_Z and origin_axes[link, 0] != 0:
            c, s = cosines[variables[link]], sines[variables[link]]
            _quarter_turn_z(poses, parent, origins, origin_axes, link, c, s)
            continue
        _compose_into(poses, parent, origins, link, frame)
        if kind == FIXED:
            for i in range(3):
                for j in range(4):
                    poses[link, i, j] = frame[i, j]
            continue
        angle = qs[m, variables[link]]
        if kind == REVOLUTE_Z:
            c, s = cosines[variables[link]], sines[variables[link]]
            for i in range(3):
                x, y = frame[i, 0], frame[i, 1]
                poses[link, i, 0] = c * x + s * y
                poses[link, i, 1] = c * y - s * x
                poses[link, i, 2] = frame[i, 2]
                poses[link, i, 3] = frame[i, 3]
            continue
        x, y, z = axes[link, 0], axes[link, 1], axes[link, 2]
        if kind == REVOLUTE:
            c, s = cosines[variables[link]], sines[variables[link]]
            t = 1.0 - c
            m00, m01, m02 = t * x * x + c, t * x * y - s * z, t * x * z + s * y
            m10, m11, m12 = t * x * y + s * z, t * y * y + c, t * y * z - s * x
            m20, m21, m22 = t * x * z - s * y, t * y * z + s * x, t * z * z + c
            for i in range(3):
                f0, f1, f2 = frame[i, 0], frame[i, 1], frame[i, 2]
                poses[link, i, 0] = f0 * m00 + f1 * m10 + f2 * m20
                poses[link, i, 1] = f0 * m01 + f1 * m11 + f2 * m21
                poses[link, i, 2] = f0 * m02 + f1 * m12 + f2 * m22
                poses[link, i, 3] = frame[i, 3]
        else:
            for i in range(3):
                f0, f1, f2 = frame[i, 0], frame[i, 1], frame[i, 2]
                poses[link, i, 0], poses[link, i, 1], poses[link, i, 2] = f0, f1, f2
                poses[link, i, 3] = frame[i, 3] + angle * (f0 * x + f1 * y + f2 * z)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def place_point(poses: FloatArray, link: int, local: FloatArray, index: int, world: FloatArray) -> None:
    """world[index] = the point local[index] of ``link`` in the world (``poses`` (L, 3, 4) or (L, 4, 4))."""
    x, y, z = local[index, 0], local[index, 1], local[index, 2]
    for k in range(3):
        world[index, k] = (
            poses[link, k, 0] * x + poses[link, k, 1] * y + poses[link, k, 2] * z + poses[link, k, 3]
        )


@numba.njit(cache=True, fastmath=True, forceinline=True)
def box_gap_at(
    x: float,
    y: float,
    z: float,
    rotations: FloatArray,
    centers: FloatArray,
    halves: FloatArray,
    kinds: npt.NDArray[np.int64],
    b: int,
) -> float:
    """Signed distance from the point (x, y, z) to obstacle ``b`` (negative inside), exact for a
    box, a sphere and a cylinder (``kinds``)."""
    dx, dy, dz = x - centers[b, 0], y - centers[b, 1], z - centers[b, 2]
    kind = kinds[b]
    if kind == SHAPE_SPHERE:
        return float(np.sqrt(dx * dx + dy * dy + dz * dz) - halves[b, 0])
    lx = rotations[b, 0, 0] * dx + rotations[b, 1, 0] * dy + rotations[b, 2, 0] * dz
    ly = rotations[b, 0, 1] * dx + rotations[b, 1, 1] * dy + rotations[b, 2, 1] * dz
    lz = rotations[b, 0, 2] * dx + rotations[b, 1, 2] * dy + rotations[b, 2, 2] * dz
    if kind == SHAPE_CYLINDER:
        radial = float(np.sqrt(lx * lx + ly * ly)) - halves[b, 0]
        axial = abs(lz) - halves[b, 2]
        if radial > 0.0 or axial > 0.0:
            radial, axial = max(radial, 0.0), max(axial, 0.0)
            return float(np.sqrt(radial * radial + axial * axial))
        return float(max(radial, axial))
    ex, ey, ez = abs(lx) - halves[b, 0], abs(ly) - halves[b, 1], abs(lz) - halves[b, 2]
    if ex > 0.0 or ey > 0.0 or ez > 0.0:
        ex, ey, ez = max(ex, 0.0), max(ey, 0.0), max(ez, 0.0)
        return float(np.sqrt(ex * ex + ey * ey + ez * ez))
    return float(max(ex, ey, ez))


@numba.njit(cache=True, fastmath=True, forceinline=True)
def point_box_gap(
    world: FloatArray,
    index: int,
    rotations: FloatArray,
    centers: FloatArray,
    halves: FloatArray,
    kinds: npt.NDArray[np.int64],
    b: int,
) -> float:
    """`box_gap_at` of the point world[index] and obstacle ``b``."""
    return box_gap_at(world[index, 0], world[index, 1], world[index, 2], rotations, centers, halves, kinds, b)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def points_apart(a: FloatArray, i: int, b: FloatArray, j: int, reach: float) -> bool:
    """Whether the points a[i] and b[j] are at least ``reach`` apart (squared distances: no root)."""
    if reach <= 0.0:
        return True
    dx, dy, dz = a[i, 0] - b[j, 0], a[i, 1] - b[j, 1], a[i, 2] - b[j, 2]
    return bool(dx * dx + dy * dy + dz * dz >= reach * reach)


def _prefetch_typed(typing_context: Any, array: Any, index: Any) -> Any:
    """Typing and code generation of `prefetch`."""

    def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
        array_type = signature.args[0]
        data = context.make_array(array_type)(context, builder, arguments[0])
        pointer = cgutils.get_item_pointer(  # type: ignore[no-untyped-call]
            context, builder, array_type, data, [arguments[1]], wraparound=False
        )
        int32 = ir.IntType(32)
        function_type = ir.FunctionType(ir.VoidType(), [pointer.type, int32, int32, int32])
        function = cgutils.get_or_insert_function(  # type: ignore[no-untyped-call]
            builder.module, function_type, "llvm.prefetch.p0"
        )
        # read, keep in all cache levels, data cache
        builder.call(function, [pointer, ir.Constant(int32, 0), ir.Constant(int32, 3), ir.Constant(int32, 1)])
        return context.get_dummy_value()

    return numba.types.void(array, index), generate


prefetch: Any = intrinsic(_prefetch_typed)
"""prefetch(array, index) in compiled code: asks the processor to bring ``array[index]`` (a 1-D
array) into cache ahead of its use; no effect on any result."""
