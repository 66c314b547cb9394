"""The validity kernel's arrays by name, and the tables derived from them once per model.

Numba-free, so that a run served by the kernels compiled ahead of time (`sphere_kernel_loading`)
lays its arguments out without importing numba: `with_derived` gives the plain tuple, in
``ALL_FIELDS`` order, that such a kernel packs itself; `validity_arrays` packs the same tuple
into numba's structref for the JIT kernels.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.codes import REVOLUTE_Z
from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid_frame import grid_frame

VALIDITY_FIELDS = (
    "lower", "upper", "root", "parents", "origins", "kinds", "axes", "variables",
    "group_links", "group_centers", "group_radii", "group_starts", "group_stops",
    "sphere_links", "sphere_centers", "sphere_radii",
    "group_roots", "node_links", "node_centers", "node_radii", "node_children", "node_first", "node_last",
    "fine_links", "fine_centers", "fine_radii",
    "box_rotations", "box_centers", "box_halves", "box_kinds", "box_lows", "box_highs",
    "table_variables", "table_lows", "table_steps", "table_counts", "table_offsets", "table_cells",
    "table_margin", "group_box_pairs", "group_pairs",
)  # fmt: skip
"""The kernel's arrays by name, in the order `kernel_arguments` lays them out."""
DERIVED_FIELDS = (
    "coarse_local", "low_x", "low_y", "low_z", "high_x", "high_y", "high_z", "unchecked", "group_order",
    "grid_frame", "grid_shape", "grid_cells", "origin_axes",
)  # fmt: skip
"""What `with_derived` adds, so that a call need not derive it."""
ALL_FIELDS = VALIDITY_FIELDS + DERIVED_FIELDS
"""Every field the kernel reads, in the order a packed tuple holds them."""
UNCHECKED = 1e300
"""Larger than any squared gap in metres: what ``unchecked`` adds for a (group, box) pair not checked."""
AXIS_TOLERANCE = 1e-10
"""How near 0 or 1 an origin's rotation entries must be for `origin_axes` to read it as quarter turns:
URDF's ``rpy`` of a half pi leaves 6e-17 in the zeros, and of pybullet's Panda's 1.57079632679 4.9e-12.
Read as 0, they move a sphere by about 1e-11 m."""


def origin_axes(origins: npt.NDArray[np.float64], kinds: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """Per link (L, 3): for a joint about z (REVOLUTE_Z) whose origin's rotation only permutes and
    flips the axes (quarter turns, as every joint of the Panda), per column of that rotation, its
    one nonzero row plus one, signed as the entry; zeros for any other link. The kinematics then
    take the parent's columns instead of multiplying by the rotation
    (`primitives.folded_link_poses`)."""
    codes = np.zeros((len(kinds), 3), dtype=np.int64)
    for link in np.flatnonzero(np.asarray(kinds) == REVOLUTE_Z):
        rotation = np.asarray(origins[link])[:3, :3]
        rounded = np.round(rotation)
        if np.max(np.abs(rotation - rounded)) > AXIS_TOLERANCE or not np.array_equal(
            np.abs(rounded).sum(axis=0), [1.0, 1.0, 1.0]
        ):
            continue
        rows = np.argmax(np.abs(rounded), axis=0)
        codes[link] = (rows + 1) * rounded[rows, [0, 1, 2]].astype(np.int64)
    return codes


_OBSTACLE_FIELDS = ("box_rotations", "box_centers", "box_halves", "box_kinds", "box_lows", "box_highs")
"""The obstacles' fields the distance grid is filled from."""
GridCells = Callable[..., npt.NDArray[np.uint8]]
"""`distance_grid.distance_grid_cells` as the serving kernels have it: (frame, shape, box_rotations,
box_centers, box_halves, box_kinds, box_lows, box_highs) -> the cells."""
GRIDS_KEPT = 16
"""Distance grids kept for obstacles seen again: a kitchen run packs 17 models of 5 obstacle sets
(a grid there takes about 1.1 ms to fill)."""
_grids: dict[tuple[bytes, GridCells], tuple[Any, ...]] = {}
"""The last ``GRIDS_KEPT`` grids by their obstacles' bytes and filler (the kernel never writes one)."""


def _distance_grid(laid_out: dict[str, Any], grid_cells: GridCells) -> tuple[Any, ...]:
    """The distance grid of the obstacles of ``laid_out``: (frame, cells per axis, cells)."""
    obstacles = {name: np.ascontiguousarray(laid_out[name]) for name in _OBSTACLE_FIELDS}
    key = (b"".join(array.tobytes() + repr(array.shape).encode() for array in obstacles.values()), grid_cells)
    if key not in _grids:
        frame, shape = grid_frame(obstacles["box_lows"].reshape(-1, 3), obstacles["box_highs"].reshape(-1, 3))
        if len(_grids) >= GRIDS_KEPT:
            del _grids[next(iter(_grids))]  # the oldest
        _grids[key] = (frame, shape, grid_cells(frame, shape, *obstacles.values()))
    return _grids[key]


def _derived(laid_out: dict[str, Any], grid_cells: GridCells) -> tuple[Any, ...]:
    """The coarse centres as x, y and z rows; the boxes' axis-aligned bounds axis by axis; the box
    pairs as a dense (group, box) table, row-major, 0 where checked and ``UNCHECKED`` where not;
    the groups with a checked box, in the order of their first pair; the obstacles' distance grid
    (`distance_grid`): its frame, cells per axis and cells; the quarter-turn origins
    (`origin_axes`)."""
    lows, highs = np.asarray(laid_out["box_lows"]), np.asarray(laid_out["box_highs"])
    groups, boxes = len(laid_out["group_radii"]), len(laid_out["box_halves"])
    unchecked = np.full(groups * boxes, UNCHECKED)
    pairs = np.asarray(laid_out["group_box_pairs"]).reshape(-1, 2)
    unchecked[pairs[:, 0] * boxes + pairs[:, 1]] = 0.0
    order = list(dict.fromkeys(int(g) for g in pairs[:, 0]))
    return (
        np.ascontiguousarray(np.asarray(laid_out["sphere_centers"]).T),
        *(np.ascontiguousarray(lows[:, axis]) for axis in range(3)),
        *(np.ascontiguousarray(highs[:, axis]) for axis in range(3)),
        unchecked,
        np.array(order, dtype=np.int64),
        *_distance_grid(laid_out, grid_cells),
        origin_axes(laid_out["origins"], laid_out["kinds"]),
    )


def with_derived(arguments: tuple[Any, ...], grid_cells: GridCells) -> tuple[Any, ...]:
    """``arguments`` (in ``VALIDITY_FIELDS`` order) followed by the tables derived from them (the
    distance grid's cells filled by ``grid_cells``): every field in ``ALL_FIELDS`` order."""
    if len(arguments) != len(VALIDITY_FIELDS):
        raise ValueError(f"expected {len(VALIDITY_FIELDS)} kernel arrays, got {len(arguments)}")
    return (*arguments, *_derived(dict(zip(VALIDITY_FIELDS, arguments, strict=True)), grid_cells))
