"""Lookup tables that settle a self-collision pair from two joint values, proved ahead of time.

Two robot links with exactly two revolute joints between them (link 5 and link 7 of
the Panda, across joints 6 and 7) are placed relative to each other by those two
joints alone. Their joint ranges are cut into a grid of cells; at each cell's centre
the validity kernel checks the pair alone with the margin raised by how far any of
the pair's sphere centres can move within the cell (a rotation by ``d`` radians moves
a point at most ``d`` times its distance from the axis, so within half a cell each
joint moves the farther link's points at most ``radius * step / 2``). A cell cleared
at that raised margin is clear at the margin everywhere inside it, so the kernel
skips the pair there, and the verdicts are unchanged: a configuration the table
clears is one the kernel would have cleared (the same level clears it at the lower
margin). Likewise a cell whose centre the kernel rejects at the margin lowered by that
much is colliding everywhere inside it (some sphere of each level stays within the
margin), so the kernel rejects the row from its joints alone. Only the speed changes:
without the table a pair a centimetre or two apart opens the fine spheres at every
configuration.

Tables are kept in memory and stored beside the spheres (`stored_spheres`: shipped with the
package for the Panda, else in the user cache), keyed by the pair's spheres, the robot's
kinematics, the limits and the margin.
"""

from __future__ import annotations

import functools
import hashlib
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.loading import sphere_kernels
from kitchen_tamp.motion.geometry.spheres.kinematics import JointAxes
from kitchen_tamp.motion.geometry.spheres.scene import SphereScene
from kitchen_tamp.motion.geometry.spheres.stored_spheres import load_pair_cells, save_pair_cells

FloatArray = npt.NDArray[np.float64]

PAIR_TABLE_VERSION = "pair-table-2"
"""Changes whenever what a stored table means changes (old files are then not read)."""
TABLE_SLACK = 0.002
"""How far (m) beyond the margin a cell's centre must be cleared: the most any of the pair's sphere
centres moves within a cell (half from each joint), which sets the cell size."""
MAX_CELLS = 600_000
"""Cells per table at most (a pair needing more gets no table)."""
_BOUNDARY_SLACK = 1e-6
"""Added to the raised margin: the kernel accepts joint values a hair outside the limits."""


@dataclass(frozen=True, eq=False)
class PairTables:
    """The tables of a scene's self-collision pairs, as the validity kernel reads them."""

    pair_tables: npt.NDArray[np.int64]
    """(P,) per checked group pair, the index of its table or -1."""
    variables: npt.NDArray[np.int64]
    """(T, 2) the two joint columns of ``qs`` each table is indexed by."""
    lows: FloatArray
    """(T, 2) where each table's first cell starts, per joint."""
    steps: FloatArray
    """(T, 2) cell size per joint (rad)."""
    counts: npt.NDArray[np.int64]
    """(T, 2) cells per joint."""
    offsets: npt.NDArray[np.int64]
    """(T,) where each table's cells start in ``cells`` (row-major over the two joints)."""
    cells: npt.NDArray[np.int8]
    """Per cell, 1 when the pair is proved clear everywhere in it, -1 when proved colliding
    everywhere in it, 0 when neither."""
    margin: float
    """The margin the tables were proved at: a kernel run at a larger margin ignores their clear
    cells, one at a smaller margin their colliding cells."""

    def kernel_arguments(self) -> tuple[Any, ...]:
        """The table arguments of ``valid_configurations``, in its order."""
        return (self.variables, self.lows, self.steps, self.counts, self.offsets, self.cells, self.margin)


def no_tables(pairs: int, margin: float = -np.inf) -> PairTables:
    """Tables for none of ``pairs`` checked group pairs."""
    return PairTables(
        np.full(pairs, -1, dtype=np.int64),
        np.zeros((0, 2), dtype=np.int64),
        np.zeros((0, 2)),
        np.ones((0, 2)),
        np.zeros((0, 2), dtype=np.int64),
        np.zeros(0, dtype=np.int64),
        np.zeros(0, dtype=np.int8),
        float(margin),
    )


def _two_joints(scene: SphereScene, g: int, h: int) -> tuple[int, int, int, int] | None:
    """(ancestor group, descendant group, nearer joint, farther joint) when exactly two revolute
    variable joints place group ``h``'s link relative to group ``g``'s, else None. Carried bodies get
    no table: a grasp is sampled anew each time, so a table would be proved for one checker only."""
    if "carried" in (scene.groups[g].role, scene.groups[h].role):
        return None
    depends = scene.tree.depends
    a, b = scene.groups[g].robot_link, scene.groups[h].robot_link
    if np.all(depends[a] <= depends[b]):
        near, far = g, h
    elif np.all(depends[b] <= depends[a]):
        near, far = h, g
    else:
        return None
    between = np.flatnonzero(depends[scene.groups[far].robot_link] & ~depends[scene.groups[near].robot_link])
    if len(between) != 2 or not np.all(scene.tree.revolute[between]):
        return None
    first, second = sorted(between.tolist(), key=lambda v: int(depends[:, v].sum()), reverse=True)
    return near, far, first, second


def _reaches(
    scene: SphereScene, far: int, first: int, second: int, at: tuple[FloatArray, JointAxes]
) -> tuple[float, float]:
    """How far (m) from each joint's axis the far group's points can be: every sphere centre and
    every bound the kernel places lies in the box of the group's sphere centres, so its corners
    bound them; the farther joint's anchor is a fixed distance from the nearer joint's. ``at``: the
    tree's link poses and joint axes at one configuration (`KinematicTree.joint_axes`)."""
    poses, axes = at
    group = scene.groups[far]
    centers = np.concatenate([scene.sphere_centers[group.spheres], scene.fine_centers[group.fine_spheres]])
    low, high = centers.min(axis=0), centers.max(axis=0)
    corners = np.array([[(low, high)[(k >> i) & 1][i] for i in range(3)] for k in range(8)])
    pose = poses[0, group.robot_link]
    world = corners @ pose[:3, :3].T + pose[:3, 3]
    anchors = axes.anchors[0]
    second_reach = float(np.max(np.linalg.norm(world - anchors[second], axis=1)))
    return float(np.linalg.norm(anchors[second] - anchors[first])) + second_reach, second_reach


def _cache_key(
    scene: SphereScene,
    near: int,
    far: int,
    variables: tuple[int, int],
    bounds: FloatArray,
    margin: float,
    steps: FloatArray,
) -> str:
    """The pair's spheres and the joints from one link to the other (not where the robot stands nor
    its other joints: they do not move one link relative to the other)."""
    digest = hashlib.sha256(PAIR_TABLE_VERSION.encode())
    layout = scene.tree.flat_layout()
    link, stop = scene.groups[far].robot_link, scene.groups[near].robot_link
    while link not in (stop, -1):
        for array in (layout.origins[link], layout.held[link], layout.kinds[link], layout.axes[link]):
            digest.update(np.ascontiguousarray(array).tobytes())
        link = int(layout.parents[link])
    for g in (near, far):
        group = scene.groups[g]
        digest.update(np.asarray([group.robot_link], dtype=np.int64).tobytes())
        for array in (
            scene.sphere_centers[group.spheres],
            scene.sphere_radii[group.spheres],
            scene.fine_centers[group.fine_spheres],
            scene.fine_radii[group.fine_spheres],
        ):
            digest.update(np.ascontiguousarray(array).tobytes())
    digest.update(np.asarray(variables, dtype=np.int64).tobytes())
    digest.update(np.asarray([*bounds.ravel(), margin, *steps, TABLE_SLACK], dtype=float).tobytes())
    return digest.hexdigest()[:32]


def _prove_cells(
    arguments: tuple[Any, ...],
    pair: npt.NDArray[np.int64],
    variables: tuple[int, int],
    lows: FloatArray,
    steps: FloatArray,
    counts: npt.NDArray[np.int64],
    raised_margin: float,
) -> npt.NDArray[np.bool_]:
    """Kernel verdicts of the pair alone at every cell centre (other joints mid-range); ``arguments``
    carry no tables, so the kernel checks the pair itself."""
    *shared, _, _ = arguments
    lower, upper = shared[0], shared[1]
    first = lows[0] + (np.arange(counts[0]) + 0.5) * steps[0]
    second = lows[1] + (np.arange(counts[1]) + 0.5) * steps[1]
    qs = np.tile((lower + upper) / 2.0, (int(counts[0] * counts[1]), 1))
    qs[:, variables[0]] = np.repeat(first, counts[1])
    qs[:, variables[1]] = np.tile(second, counts[0])
    kernels = sphere_kernels()
    no_box_pairs = np.zeros((0, 2), dtype=np.int64)
    alone = (*shared, no_box_pairs, np.concatenate([pair, [-1]]).reshape(1, 3).astype(np.int64))
    valid = kernels.valid(np.ascontiguousarray(qs), kernels.pack(alone), raised_margin, False)
    return np.asarray(valid, dtype=np.bool_)


@functools.lru_cache(maxsize=64)
def _stored_cells(key: str) -> npt.NDArray[np.int8] | None:
    return load_pair_cells(key)


def _store_cells(key: str, cells: npt.NDArray[np.int8]) -> None:
    save_pair_cells(key, cells)
    _stored_cells.cache_clear()


def pair_tables(scene: SphereScene, arguments: tuple[Any, ...], margin: float) -> PairTables:
    """Tables for the checked self pairs of ``scene`` placed by two joints, proved at ``margin``
    with the kernel ``arguments`` laid out without tables (`sphere_kernel_layout.kernel_arguments`)."""
    lower, upper = np.asarray(arguments[0], dtype=float), np.asarray(arguments[1], dtype=float)
    middle = (lower + upper) / 2.0
    at_middle = scene.tree.joint_axes(middle[None])
    pair_index = np.full(len(scene.group_pairs), -1, dtype=np.int64)
    variables: list[tuple[int, int]] = []
    lows: list[FloatArray] = []
    steps: list[FloatArray] = []
    counts: list[npt.NDArray[np.int64]] = []
    offsets: list[int] = []
    cells: list[npt.NDArray[np.int8]] = []
    stored = 0
    for k, (g, h) in enumerate(scene.group_pairs.tolist()):
        placed = _two_joints(scene, g, h)
        if placed is None:
            continue
        near, far, first, second = placed
        reaches = np.array(_reaches(scene, far, first, second, at_middle))
        span = upper[[first, second]] - lower[[first, second]]
        count = np.maximum(np.ceil(span * reaches / TABLE_SLACK), 1).astype(np.int64)
        if int(np.prod(count)) > MAX_CELLS:
            continue
        step = span / count
        low = lower[[first, second]]
        key = _cache_key(scene, near, far, (first, second), np.stack([low, span]), margin, step)
        proved = _stored_cells(key)
        if proved is None or len(proved) != int(np.prod(count)):
            slack = float(np.dot(reaches, step)) / 2.0 + _BOUNDARY_SLACK
            pair = np.array([g, h], dtype=np.int64)
            cell_centres = (arguments, pair, (first, second), low, step, count)
            clear = _prove_cells(*cell_centres, margin + slack)
            colliding = ~_prove_cells(*cell_centres, margin - slack)
            proved = clear.astype(np.int8) - colliding.astype(np.int8)
            _store_cells(key, proved)
        if np.all(proved > 0):  # clear everywhere: one cell says so, and costs no lookup
            count, step, proved = np.ones(2, dtype=np.int64), span.astype(float), proved[:1]
        pair_index[k] = len(variables)
        variables.append((first, second))
        lows.append(low)
        steps.append(step)
        counts.append(count)
        offsets.append(stored)
        cells.append(proved)
        stored += len(proved)
    if not variables:
        return no_tables(len(scene.group_pairs), margin)
    return PairTables(
        pair_index,
        np.array(variables, dtype=np.int64),
        np.array(lows, dtype=float),
        np.array(steps, dtype=float),
        np.array(counts, dtype=np.int64),
        np.array(offsets, dtype=np.int64),
        np.concatenate(cells),
        float(margin),
    )
