"""How densely a straight joint-space move is checked: one rule for every checker and the judge.

A move from ``q0`` to ``q1`` is cut into equal intervals no longer than a
resolution in the Euclidean norm over the joints (so no single joint moves
further than that either), and interior states are visited coarse to fine
(midpoint first), so a blocked move usually fails after a few checks. The
planners' collision checkers (``motion``, ``world``) and the judge
(``execute``) all space their states by this rule; the judge checks at
``JUDGE_RESOLUTION_RAD`` and planners check what they hand over at it too.
"""

from __future__ import annotations

import math
from typing import Final

import numpy as np
import numpy.typing as npt

JUDGE_RESOLUTION_RAD: Final = 0.005
"""Joint-space spacing (rad, Euclidean) of the states the judge checks."""

PLANNING_RESOLUTION_RAD: Final = 0.01
"""Default spacing (rad, Euclidean) at which planners and their checkers test edges and segments
while searching (what they hand over is checked again at ``JUDGE_RESOLUTION_RAD``)."""


def interval_count(q0: npt.ArrayLike, q1: npt.ArrayLike, resolution: float) -> int:
    """Number of equal intervals the straight move q0 -> q1 is cut into at ``resolution``."""
    if resolution <= 0.0:
        raise ValueError(f"resolution must be positive, got {resolution}")
    return max(1, math.ceil(joint_distance(q0, q1) / resolution))


def joint_distance(q0: npt.ArrayLike, q1: npt.ArrayLike) -> float:
    """Euclidean distance over the joints, summed joint by joint in order.

    Not ``np.linalg.norm``: its sum goes through BLAS, whose order of additions depends on
    the CPU's vector width, and a move whose length is a whole number of resolutions (an
    RRT step is) would then be cut into one interval more on one machine than on another.
    The compiled RRT-Connect loop and shortcut sum the same way
    (``rrt_connect_kernel.joint_distance``)."""
    squared = 0.0
    for d in (np.asarray(q1, dtype=float) - np.asarray(q0, dtype=float)).tolist():
        squared += d * d
    return math.sqrt(squared)


def coarse_to_fine_order(count: int) -> npt.NDArray[np.intp]:
    """A permutation of range(count) visiting a halving grid: middle first, then quarters..."""
    positions = np.arange(1, count + 1)
    lowest_set_bit = positions & -positions
    return np.argsort(-lowest_set_bit, kind="stable")


def interior_fractions(q0: npt.ArrayLike, q1: npt.ArrayLike, resolution: float) -> npt.NDArray[np.float64]:
    """Fractions in (0, 1) of the interior states of q0 -> q1 at ``resolution``, coarse to fine."""
    intervals = interval_count(q0, q1, resolution)
    return np.asarray(np.arange(1, intervals)[coarse_to_fine_order(intervals - 1)] / intervals, dtype=float)
