"""What the certified segment walk (`certified_segments`) reads beside the validity kernel's arrays:
how fast each group of spheres can move per radian of each joint, and a medium level of spheres
between a group's bound and its coarse spheres. Computed once per model, in Python, by
`validity_arrays` (packed with the kernel's arrays).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.primitives import PRISMATIC, REVOLUTE, REVOLUTE_Z

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

MEDIUM_PER_GROUP = 4
"""Medium spheres per group at most: each holds a quarter of the group's coarse spheres (halved
twice across the widest extent of their centres), so a pair of groups is bounded at the medium
level by 16 distances instead of the coarse level's 256."""


def group_reaches(
    parents: IntArray,
    origins: FloatArray,
    kinds: IntArray,
    variables: IntArray,
    lower: FloatArray,
    upper: FloatArray,
    group_links: IntArray,
    carried: Sequence[FloatArray],
) -> FloatArray:
    """(G, L): per group and link, how fast the points ``carried[g]`` (in the frame of group g's
    link) can move per radian (or metre) of the link's joint: for a revolute ancestor (or the
    group's own link), a bound on their distance from the joint's origin (the largest local
    distance, plus each joint origin's offset up the chain, plus a prismatic joint's longest
    travel; positive); 1 for a prismatic ancestor; 0 for a link that does not carry the group."""
    reaches = np.zeros((len(group_links), len(parents)))
    for g, link in enumerate(group_links):
        points = np.asarray(carried[g]).reshape(-1, 3)
        distance = float(np.max(np.linalg.norm(points, axis=1)))
        link = int(link)
        while link >= 0:
            column = int(variables[link])
            if column >= 0 and kinds[link] in (REVOLUTE, REVOLUTE_Z):
                reaches[g, link] = max(distance, 1e-12)  # positive: the link carries the group
            elif column >= 0 and kinds[link] == PRISMATIC:
                reaches[g, link] = 1.0
                distance += max(abs(float(lower[column])), abs(float(upper[column])))
            distance += float(np.linalg.norm(origins[link, :3, 3]))
            link = int(parents[link])
    return reaches


def _halves(centers: FloatArray, members: npt.NDArray[np.intp], parts: int) -> list[npt.NDArray[np.intp]]:
    """``members`` cut into ``parts`` (a power of two) by halving across the widest extent."""
    if parts == 1 or len(members) < 2:
        return [members]
    points = centers[members]
    axis = int(np.argmax(points.max(axis=0) - points.min(axis=0)))
    order = members[np.argsort(points[:, axis], kind="stable")]
    middle = len(order) // 2
    return _halves(centers, order[:middle], parts // 2) + _halves(centers, order[middle:], parts // 2)


def medium_spheres(
    centers: FloatArray, radii: FloatArray, starts: IntArray, stops: IntArray
) -> tuple[FloatArray, FloatArray, IntArray, IntArray]:
    """(centres (M, 3), radii (M,), first and last index per group): per group, spheres each holding
    a part of its coarse spheres ``centers[starts[g]:stops[g]]`` (centred mid-box of their
    centres, reaching the farthest sphere's far side)."""
    medium_centers: list[FloatArray] = []
    medium_radii: list[float] = []
    first, last = [], []
    for start, stop in zip(starts, stops, strict=True):
        first.append(len(medium_radii))
        members = np.arange(int(start), int(stop))
        if len(members):
            for part in _halves(centers, members, MEDIUM_PER_GROUP):
                points = centers[part]
                center = (points.min(axis=0) + points.max(axis=0)) / 2.0
                medium_centers.append(center)
                medium_radii.append(float(np.max(np.linalg.norm(points - center, axis=1) + radii[part])))
        last.append(len(medium_radii))
    return (
        np.array(medium_centers, dtype=float).reshape(-1, 3),
        np.array(medium_radii, dtype=float),
        np.array(first, dtype=np.int64),
        np.array(last, dtype=np.int64),
    )
