"""The arrays the compiled validity kernel (`sphere_kernels.valid_configurations`) takes, laid out
from a `SphereScene`: the kinematic tree, the coarse spheres with one bound per group, the fine
spheres in a binary tree of bounding spheres per group (their centres as x, y and z rows), the
obstacle boxes and the checked pairs in the order most likely to meet a collision first.

A group's fine spheres are halved across the widest extent of their centres until a leaf holds
at most ``LEAF_SIZE``; spheres are stored leaf by leaf, so every node's spheres are one range. A
bound holds every sphere under it (centre distance plus radius), so a bound clear of an
obstacle proves its spheres clear.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.codes import FIXED, REVOLUTE, REVOLUTE_Z, SKIPPED
from kitchen_tamp.motion.geometry.spheres.kinematics import TreeLayout
from kitchen_tamp.motion.geometry.spheres.pair_tables import PairTables, no_tables
from kitchen_tamp.motion.geometry.spheres.scene import SphereGroup, SphereScene

FloatArray = npt.NDArray[np.float64]
IndexArray = npt.NDArray[np.intp]

LEAF_SIZE = 96
"""Spheres per leaf of a bounding-sphere tree at most: the kernel places a leaf's spheres and tests
two leaves against each other in SIMD lanes, where a descent costs one unpredictable branch per
node pair, so shallow trees of large leaves win (measured on the motion.py kitchen samples, per
CPU s: leaves of 4 spheres 1.17M uniform; of 24, 1.44M uniform and 363k within 1e-6 rad of the
spheres' own contact; of 48, 1.49M and 405k; of 96, 1.48M and 427k)."""


def _split(centers: FloatArray, members: IndexArray) -> tuple[IndexArray, IndexArray]:
    """``members`` halved across the widest extent of their centres."""
    points = centers[members]
    axis = int(np.argmax(points.max(axis=0) - points.min(axis=0)))
    order = members[np.argsort(points[:, axis], kind="stable")]
    return order[: len(order) // 2], order[len(order) // 2 :]


def _bound(centers: FloatArray, radii: FloatArray) -> tuple[FloatArray, float]:
    """A sphere holding every sphere given: centred mid-box, the farthest reach as radius."""
    center = (centers.min(axis=0) + centers.max(axis=0)) / 2.0
    return center, float(np.max(np.linalg.norm(centers - center, axis=1) + radii))


def _likely_first(scene: SphereScene, group_box_pairs: IndexArray) -> IndexArray:
    """(group, box) pairs ordered so that a collision tends to be met early: the hand's end of
    the arm and carried bodies first (they sweep the most), then the largest boxes."""
    volume = np.prod(scene.boxes.half_extents, axis=1)
    links = np.array([g.robot_link for g in scene.groups])
    order = np.lexsort((-volume[group_box_pairs[:, 1]], -links[group_box_pairs[:, 0]]))
    return group_box_pairs[order]


class _Tree:
    """Bounding-sphere trees of the groups, built node by node (spheres stored leaf by leaf)."""

    def __init__(self, centers: FloatArray, radii: FloatArray) -> None:
        self.sphere_centers, self.sphere_radii = centers, radii
        self.links: list[int] = []
        self.centers: list[FloatArray] = []
        self.radii: list[float] = []
        self.children: list[list[int]] = []
        self.first: list[int] = []
        self.last: list[int] = []
        self.order: list[IndexArray] = []
        self.stored = 0

    def build(self, members: IndexArray, link: int) -> int:
        node = len(self.radii)
        center, radius = _bound(self.sphere_centers[members], self.sphere_radii[members])
        self.links.append(link)
        self.centers.append(center)
        self.radii.append(radius)
        self.children.append([-1, -1])
        self.first.append(self.stored)
        self.last.append(self.stored)
        if len(members) <= LEAF_SIZE:
            self.order.append(members)
            self.stored += len(members)
        else:
            low, high = _split(self.sphere_centers, members)
            self.children[node] = [self.build(low, link), self.build(high, link)]
        self.last[node] = self.stored
        return node

    def graft(self, grown: _Tree, group: SphereGroup) -> int:
        """Add ``grown`` (one group's tree over its own spheres) for ``group``; its root node."""
        root, offset = len(self.radii), group.fine_spheres.start
        self.links.extend([group.robot_link] * len(grown.radii))
        self.centers.extend(grown.centers)
        self.radii.extend(grown.radii)
        self.children.extend([[c + root if c >= 0 else -1 for c in pair] for pair in grown.children])
        self.first.extend(f + self.stored for f in grown.first)
        self.last.extend(last + self.stored for last in grown.last)
        self.order.extend(members + offset for members in grown.order)
        self.stored += grown.stored
        return root


def _group_tree(scene: SphereScene, spheres: slice) -> _Tree:
    return _grown_tree(scene.fine_centers[spheres].tobytes(), scene.fine_radii[spheres].tobytes())


@functools.lru_cache(maxsize=64)
def _grown_tree(centers: bytes, radii: bytes) -> _Tree:
    """The tree of one group's fine spheres (given as bytes), indices its own: grown once per
    process for the same spheres (the robot's links are the same in every scene)."""
    tree = _Tree(np.frombuffer(centers).reshape(-1, 3), np.frombuffer(radii))
    tree.build(np.arange(len(tree.sphere_radii)), 0)
    return tree


def _folded_tree(layout: TreeLayout) -> tuple[tuple[Any, ...], npt.NDArray[np.int64], FloatArray]:
    """The tree as the validity kernel computes it, with the fixed links folded away: ((root,
    parents, origins, kinds, axes, variables), carrier (L,), offset (L, 4, 4)), where each link's
    pose is its carrier's (the root or a moving link) times its offset. A moving link's parent
    becomes its parent's carrier, its origin the parent's offset times its own; a revolute joint
    about z is marked REVOLUTE_Z, a folded link SKIPPED."""
    root, parents, origins, kinds, axes, variables = layout.kernel_arrays()
    count = len(parents)
    carrier = np.arange(count, dtype=np.int64)
    offset = np.broadcast_to(np.eye(4), (count, 4, 4)).copy()
    folded_parents, folded_origins, folded_kinds = parents.copy(), origins.copy(), kinds.copy()
    for link in range(count):
        parent = int(parents[link])
        if parent < 0:
            continue
        if kinds[link] == FIXED:
            carrier[link] = carrier[parent]
            offset[link] = offset[parent] @ origins[link]
            folded_kinds[link] = SKIPPED
            continue
        folded_parents[link] = carrier[parent]
        folded_origins[link] = offset[parent] @ origins[link]
        if kinds[link] == REVOLUTE and np.array_equal(axes[link], [0.0, 0.0, 1.0]):
            folded_kinds[link] = REVOLUTE_Z
    arrays = (root, folded_parents, folded_origins, folded_kinds, axes, variables)
    return arrays, carrier, offset


def _on_carriers(
    links: npt.NDArray[np.int64], centers: FloatArray, carrier: npt.NDArray[np.int64], offset: FloatArray
) -> tuple[npt.NDArray[np.int64], FloatArray]:
    """Points given on ``links`` re-expressed on the links' carriers."""
    moved = np.einsum("nij,nj->ni", offset[links, :3, :3], centers) + offset[links, :3, 3]
    return carrier[links].astype(np.int64), np.ascontiguousarray(moved)


def _rows(links: npt.NDArray[np.int64], points: FloatArray) -> tuple[npt.NDArray[np.int64], FloatArray]:
    """(links, points as x, y and z rows): the fine spheres' layout, which the kernel places a
    leaf at a time in SIMD lanes."""
    return links, np.ascontiguousarray(points.T)


def kernel_arguments(scene: SphereScene, lower: FloatArray, upper: FloatArray) -> tuple[Any, ...]:
    """Every argument of ``valid_configurations`` after ``qs`` and before ``margin``, without pair
    tables (`with_pair_tables` adds them); the checked pairs are last (``group_box_pairs``, then
    ``group_pairs`` with each pair's table, here -1)."""
    tables = no_tables(len(scene.group_pairs))
    kinematics, carrier, offset = _folded_tree(scene.tree.flat_layout())
    group_centers, group_radii = [], []
    for group in scene.groups:
        center, radius = _bound(scene.sphere_centers[group.spheres], scene.sphere_radii[group.spheres])
        group_centers.append(center)
        group_radii.append(radius)
    tree = _Tree(scene.fine_centers, scene.fine_radii)
    roots = [tree.graft(_group_tree(scene, group.fine_spheres), group) for group in scene.groups]
    order = np.concatenate(tree.order) if tree.order else np.zeros(0, dtype=np.intp)
    boxes = scene.boxes
    reach = np.einsum("bij,bj->bi", np.abs(boxes.rotations), boxes.half_extents)

    def indices(values: list[int] | IndexArray) -> npt.NDArray[np.int64]:
        return np.asarray(values, dtype=np.int64)

    def carried(
        links: list[int] | IndexArray, centers: FloatArray
    ) -> tuple[npt.NDArray[np.int64], FloatArray]:
        return _on_carriers(indices(links), np.asarray(centers, dtype=float).reshape(-1, 3), carrier, offset)

    group_links, group_centers_carried = carried(
        [g.robot_link for g in scene.groups], np.array(group_centers)
    )
    return (
        lower,
        upper,
        *kinematics,
        group_links,
        group_centers_carried,
        np.array(group_radii, dtype=float),
        indices([g.spheres.start for g in scene.groups]),
        indices([g.spheres.stop for g in scene.groups]),
        *carried(scene.sphere_links, scene.sphere_centers),
        scene.sphere_radii,
        indices(roots),
        *carried(tree.links, np.array(tree.centers)),
        np.array(tree.radii, dtype=float),
        np.array(tree.children, dtype=np.int64).reshape(-1, 2),
        indices(tree.first),
        indices(tree.last),
        *_rows(*carried(scene.fine_links[order], scene.fine_centers[order])),
        np.ascontiguousarray(scene.fine_radii[order]),
        np.ascontiguousarray(boxes.rotations),
        np.ascontiguousarray(boxes.centers),
        np.ascontiguousarray(boxes.half_extents),
        np.ascontiguousarray(boxes.kinds),
        boxes.centers - reach,
        boxes.centers + reach,
        *tables.kernel_arguments(),
        indices(_likely_first(scene, scene.group_box_pairs)).reshape(-1, 2),
        np.column_stack([indices(scene.group_pairs).reshape(-1, 2), tables.pair_tables]).astype(np.int64),
    )


def with_pair_tables(arguments: tuple[Any, ...], tables: PairTables) -> tuple[Any, ...]:
    """``arguments`` of `kernel_arguments` with ``tables`` in place of the tables they carry (the
    trees are not built again)."""
    table_arguments = tables.kernel_arguments()
    *laid_out, group_box_pairs, group_pairs = arguments
    geometry = laid_out[: len(laid_out) - len(table_arguments)]
    named = np.column_stack([group_pairs[:, :2], tables.pair_tables]).astype(np.int64)
    return (*geometry, *table_arguments, group_box_pairs, named)
