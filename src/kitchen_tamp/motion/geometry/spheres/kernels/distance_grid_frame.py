"""Where the obstacles' distance grid lies and how fine it is (`distance_grid`), without numba.

Kept apart from the compiled kernels, as `codes` is, so that a run served by the kernels compiled
ahead of time lays the grid out (`validity_fields.with_derived`) without importing numba.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

GRID_REACH = 0.3
"""How far (m) the grid reaches beyond the obstacles: more than any group's bound plus the margin
(the Panda's largest bound is 0.19 m), so that a group far from everything is cleared outside the
grid as well as in it."""
GRID_UNIT = GRID_REACH / 255
"""What one step of a cell's byte stands for (m): ``GRID_REACH`` at 255."""
GRID_STEP = 0.04
"""A cell's edge (m), unless the grid would then have more than ``GRID_MAX_CELLS`` cells."""
GRID_MAX_CELLS = 1 << 18
"""Cells at most (256 KiB): a larger scene gets larger cells."""


def grid_frame(
    box_lows: npt.NDArray[np.float64], box_highs: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The grid over obstacles with these axis-aligned bounds ((B, 3) each): its frame (lowest
    corner x, y, z; cell edge; the clearance outside it, ``GRID_REACH``) and its cells per axis.
    Without obstacles, a grid of no cells that clears nothing (the kernel has nothing to test)."""
    if len(box_lows) == 0:
        return np.array([0.0, 0.0, 0.0, 1.0, 0.0]), np.zeros(3, dtype=np.int64)
    low = np.asarray(box_lows, dtype=float).min(axis=0) - GRID_REACH
    extent = np.asarray(box_highs, dtype=float).max(axis=0) + GRID_REACH - low
    step = max(GRID_STEP, float(np.prod(extent) / GRID_MAX_CELLS) ** (1 / 3))
    shape = np.array([max(1, math.ceil(float(e) / step)) for e in extent], dtype=np.int64)
    while int(np.prod(shape)) > GRID_MAX_CELLS:  # rounding up each axis can overshoot the cap
        step *= 1.01
        shape = np.array([max(1, math.ceil(float(e) / step)) for e in extent], dtype=np.int64)
    return np.array([*low, step, GRID_REACH]), shape
