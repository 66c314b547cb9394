"""The kinematics of eight configurations at once (`simd.Doubles8` lanes), for the screen in
`screen`: each joint's sine and cosine, then each link's pose, as `primitives.folded_link_poses`
computes them for one configuration.

Everything is laid out lane innermost in 1-D arrays: a joint's eight values at ``j * LANES``, a
link's pose as 12 rows of eight (its top 3x4 entries, row-major) at ``link * 12 * LANES``.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.codes import FIXED, REVOLUTE, REVOLUTE_Z, SKIPPED
from kitchen_tamp.motion.geometry.spheres.kernels.lanes.simd import (
    WIDTH,
    at_least8,
    floor8,
    load8,
    splat8,
    store8,
)
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import (
    COSINE_TERMS,
    HALF_PI_HIGH,
    HALF_PI_LOW,
    SINE_TERMS,
    TWO_OVER_PI,
)

FloatArray = npt.NDArray[np.float64]

LANES = WIDTH
"""Configurations side by side."""
ALL_LANES = (1 << LANES) - 1
"""The bit mask of every lane."""
LIMIT_TOLERANCE = 1e-9
"""How far past a joint limit a value still counts as within it: the validity kernel's tolerance."""

Chain = Any
"""The links as `primitives.folded_link_poses` takes them, as fields: ``root``, ``parents``,
``origins``, ``kinds``, ``axes``, ``variables`` and ``origin_axes`` (a `ValidityArrays`). One
object, not a tuple of seven arrays: a compiled call counts a reference to each array it is passed
(`buffers`), and the links are passed once per link."""


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _lane_direction(poses: FloatArray, row: int, x: float, y: float, z: float) -> Any:
    """One world coordinate of the direction (x, y, z) of a link, in every lane (``row``: where the
    link's pose row of that coordinate starts in ``poses``)."""
    return load8(poses, row) * x + load8(poses, row + LANES) * y + load8(poses, row + 2 * LANES) * z


@numba.njit(cache=True, fastmath=True, forceinline=True)
def lane_point(poses: FloatArray, row: int, x: float, y: float, z: float) -> Any:
    """One world coordinate of the point (x, y, z) of a link, in every lane (``row`` as above)."""
    return _lane_direction(poses, row, x, y, z) + load8(poses, row + 3 * LANES)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def within_limits(values: FloatArray, lower: FloatArray, upper: FloatArray) -> int:
    """The lanes whose every joint is within its limits (bit ``k`` for lane ``k``)."""
    inside = ALL_LANES
    for j in range(lower.shape[0]):
        value = load8(values, j * LANES)
        inside &= at_least8(value, lower[j] - LIMIT_TOLERANCE) & at_least8(upper[j] + LIMIT_TOLERANCE, value)
    return inside


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _sines_cosines(values: FloatArray, sines: FloatArray, cosines: FloatArray) -> None:
    """`primitives.sine_cosine` of every lane of every joint: the same reduction and polynomials,
    the quadrant's swaps and signs as products with 0 and 1 (exact) instead of branches."""
    s1, s2, s3, s4, s5, s6, s7 = SINE_TERMS
    c1, c2, c3, c4, c5, c6, c7 = COSINE_TERMS
    for j in range(values.shape[0] // LANES):
        x = load8(values, j * LANES)
        turns = floor8(x * TWO_OVER_PI + 0.5)
        r = (x - turns * HALF_PI_HIGH) - turns * HALF_PI_LOW
        z = r * r
        sine = r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * (s6 + z * s7))))))
        cosine = 1.0 - 0.5 * z + z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * (c6 + z * c7))))))
        quadrant = turns - 4.0 * floor8(turns * 0.25)
        half = floor8(quadrant * 0.5)  # 1 in the quadrants where the sine is negative
        odd = quadrant - 2.0 * half  # 1 where sine and cosine swap
        kept = 1.0 - odd
        pairs = floor8((quadrant + 1.0) * 0.5)  # odd in the quadrants where the cosine is negative
        cosine_sign = 1.0 - 2.0 * (pairs - 2.0 * floor8(pairs * 0.5))
        store8(sines, j * LANES, (1.0 - 2.0 * half) * (sine * kept + cosine * odd))
        store8(cosines, j * LANES, cosine_sign * (cosine * kept + sine * odd))


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _quarter_turn_z(
    poses: FloatArray, parent: int, link: int, chain: Chain, sines: FloatArray, cosines: FloatArray
) -> None:
    """`primitives._quarter_turn_z` in every lane: the parent's columns permuted and signed (the
    origin's rotation), turned about z, and the origin's translation."""
    origin_axes, origins, variable = chain.origin_axes, chain.origins, chain.variables[link]
    a0, a1, a2 = origin_axes[link, 0], origin_axes[link, 1], origin_axes[link, 2]
    r0, r1, r2 = abs(a0) - 1, abs(a1) - 1, abs(a2) - 1
    g0, g1, g2 = (1.0 if a0 > 0 else -1.0), (1.0 if a1 > 0 else -1.0), (1.0 if a2 > 0 else -1.0)
    t0, t1, t2 = origins[link, 0, 3], origins[link, 1, 3], origins[link, 2, 3]
    c, s = load8(cosines, variable * LANES), load8(sines, variable * LANES)
    for i in range(3):
        above, here = (parent * 12 + 4 * i) * LANES, (link * 12 + 4 * i) * LANES
        f0 = g0 * load8(poses, above + r0 * LANES)
        f1 = g1 * load8(poses, above + r1 * LANES)
        store8(poses, here + 3 * LANES, lane_point(poses, above, t0, t1, t2))
        store8(poses, here, c * f0 + s * f1)
        store8(poses, here + LANES, c * f1 - s * f0)
        store8(poses, here + 2 * LANES, g2 * load8(poses, above + r2 * LANES))


@numba.njit(cache=True, fastmath=True, forceinline=True)
def _moved_link(
    poses: FloatArray,
    parent: int,
    link: int,
    chain: Chain,
    values: FloatArray,
    sines: FloatArray,
    cosines: FloatArray,
) -> None:
    """poses[link] = poses[parent] @ origins[link], moved by the link's joint (FIXED, REVOLUTE_Z,
    REVOLUTE or PRISMATIC about its axis), in every lane."""
    origins, axes = chain.origins, chain.axes
    kind, variable = chain.kinds[link], max(chain.variables[link], 0)
    x, y, z = axes[link, 0], axes[link, 1], axes[link, 2]
    c, s = load8(cosines, variable * LANES), load8(sines, variable * LANES)
    value = load8(values, variable * LANES)
    for i in range(3):
        above, here = (parent * 12 + 4 * i) * LANES, (link * 12 + 4 * i) * LANES
        f0 = _lane_direction(poses, above, origins[link, 0, 0], origins[link, 1, 0], origins[link, 2, 0])
        f1 = _lane_direction(poses, above, origins[link, 0, 1], origins[link, 1, 1], origins[link, 2, 1])
        f2 = _lane_direction(poses, above, origins[link, 0, 2], origins[link, 1, 2], origins[link, 2, 2])
        f3 = lane_point(poses, above, origins[link, 0, 3], origins[link, 1, 3], origins[link, 2, 3])
        if kind == FIXED:
            n0, n1, n2 = f0, f1, f2
        elif kind == REVOLUTE_Z:
            n0, n1, n2 = c * f0 + s * f1, c * f1 - s * f0, f2
        elif kind == REVOLUTE:
            t = 1.0 - c
            n0 = f0 * (t * x * x + c) + f1 * (t * x * y + s * z) + f2 * (t * x * z - s * y)
            n1 = f0 * (t * x * y - s * z) + f1 * (t * y * y + c) + f2 * (t * y * z + s * x)
            n2 = f0 * (t * x * z + s * y) + f1 * (t * y * z - s * x) + f2 * (t * z * z + c)
        else:
            n0, n1, n2 = f0, f1, f2
            f3 = f3 + value * (f0 * x + f1 * y + f2 * z)
        store8(poses, here, n0)
        store8(poses, here + LANES, n1)
        store8(poses, here + 2 * LANES, n2)
        store8(poses, here + 3 * LANES, f3)


@numba.njit(cache=True, fastmath=True, forceinline=True)
def lane_link_poses(
    chain: Chain, values: FloatArray, sines: FloatArray, cosines: FloatArray, poses: FloatArray
) -> None:
    """Every kept link's pose (into ``poses``) at the lanes' configurations (``values``), as
    `primitives.folded_link_poses` places them; the sines and cosines into ``sines``, ``cosines``."""
    _sines_cosines(values, sines, cosines)
    root, parents, kinds, origin_axes = chain.root, chain.parents, chain.kinds, chain.origin_axes
    for link in range(parents.shape[0]):
        kind, parent = kinds[link], parents[link]
        if kind == SKIPPED:
            continue
        if parent < 0:
            for e in range(12):
                store8(poses, (link * 12 + e) * LANES, splat8(root[e // 4, e % 4]))
        elif kind == REVOLUTE_Z and origin_axes[link, 0] != 0:
            _quarter_turn_z(poses, parent, link, chain, sines, cosines)
        else:
            _moved_link(poses, parent, link, chain, values, sines, cosines)
