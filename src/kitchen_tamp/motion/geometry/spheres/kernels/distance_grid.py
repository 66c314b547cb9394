"""A grid of the obstacles' distances, so that the validity kernel clears a far group in one lookup.

Per configuration the kernel placed each group's bound and tested it against every obstacle's
axis-aligned bounds: 11 groups on MotionBenchMaker's scenes, about 13 ns each whatever the number
of obstacles, the largest part of a free configuration's check after the kinematics. With this
grid a group is cleared by one read when no obstacle comes within its reach.

Each cell holds a lower bound of the distance from every point of the cell to the nearest
obstacle (the exact distance from the cell's centre, less the half-diagonal: distances change no
faster than the point), rounded down to ``GRID_UNIT`` and capped at ``GRID_REACH``. The grid
spans the obstacles' axis-aligned bounds grown by ``GRID_REACH``, so a point outside it is at
least ``GRID_REACH`` from every obstacle. Verdicts are unchanged: a group the grid clears is one
every test after it would have cleared, since its bound's centre is at least its reach from every
obstacle (`validity.valid_rows`).

The cells are filled by `distance_grid_cells` (compiled: the ahead-of-time module exports it too);
the grid's frame and size, which need no compiler, by `distance_grid_frame.grid_frame`.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid_frame import GRID_REACH, GRID_UNIT
from kitchen_tamp.motion.geometry.spheres.kernels.primitives import box_gap_at

FloatArray = npt.NDArray[np.float64]


@numba.njit(cache=True)
def distance_grid_cells(
    frame: FloatArray,
    shape: npt.NDArray[np.int64],
    rotations: FloatArray,
    centers: FloatArray,
    halves: FloatArray,
    kinds: npt.NDArray[np.int64],
    lows: FloatArray,
    highs: FloatArray,
) -> npt.NDArray[np.uint8]:
    """The cells (x-major, then y, then z) of the grid whose ``frame`` is (lowest corner x, y, z,
    cell edge, ...) and ``shape`` its cells per axis (`distance_grid_frame.grid_frame`): per cell,
    the distance from any point of it to the nearest obstacle (`primitives.box_gap_at` at its
    centre less the half-diagonal), in units of ``GRID_UNIT`` rounded down, between 0 and 255.
    Each obstacle is measured only from the cells within ``GRID_REACH`` of its axis-aligned
    bounds (``lows``, ``highs``): the others hold ``GRID_REACH`` for it."""
    step = frame[3]
    half_diagonal = step * np.sqrt(3.0) / 2.0
    # A cell nothing comes near holds GRID_REACH.
    nearest = np.full(shape[0] * shape[1] * shape[2], GRID_REACH + half_diagonal)
    spans = np.empty((3, 2), dtype=np.int64)
    for b in range(kinds.shape[0]):
        for axis in range(3):
            grown = GRID_REACH + half_diagonal
            first = int(np.floor((lows[b, axis] - grown - frame[axis]) / step))
            last = int(np.ceil((highs[b, axis] + grown - frame[axis]) / step))
            spans[axis, 0], spans[axis, 1] = max(first, 0), min(last, shape[axis])
        for i in range(spans[0, 0], spans[0, 1]):
            x = frame[0] + (i + 0.5) * step
            for j in range(spans[1, 0], spans[1, 1]):
                y = frame[1] + (j + 0.5) * step
                for k in range(spans[2, 0], spans[2, 1]):
                    z = frame[2] + (k + 0.5) * step
                    cell = (i * shape[1] + j) * shape[2] + k
                    gap = box_gap_at(x, y, z, rotations, centers, halves, kinds, b)
                    nearest[cell] = min(nearest[cell], gap)
    cells = np.empty(nearest.shape[0], dtype=np.uint8)
    for cell in range(nearest.shape[0]):
        # Rounded down, and a hair more, so that reading a byte back never overstates it.
        units = np.floor((nearest[cell] - half_diagonal) / GRID_UNIT - 1e-6)
        cells[cell] = np.uint8(min(max(units, 0.0), 255.0))
    return cells


@numba.njit(cache=True, fastmath=True, forceinline=True)
def grid_clearance(
    dx: float,
    dy: float,
    dz: float,
    scale: float,
    outside: float,
    shape: npt.NDArray[np.int64],
    cells: npt.NDArray[np.uint8],
) -> float:
    """A lower bound of the distance to every obstacle from the point (dx, dy, dz) away from the
    grid's lowest corner, ``scale`` the inverse of its cell's edge: the point's cell's, or
    ``outside`` beyond the grid (the frame's last value: ``GRID_REACH``, or 0 for a grid of no
    cells, which then clears nothing). A point on a face between two cells may be read in either:
    both bounds hold there."""
    i = int(np.floor(dx * scale))
    j = int(np.floor(dy * scale))
    k = int(np.floor(dz * scale))
    if i < 0 or j < 0 or k < 0 or i >= shape[0] or j >= shape[1] or k >= shape[2]:
        return outside
    return float(cells[(i * shape[1] + j) * shape[2] + k] * GRID_UNIT)
