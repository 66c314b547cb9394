"""The sphere model's verdicts in plain numpy, pair by pair: the reference the compiled kernel
(`sphere_kernels.valid_configurations`) is tested against.

A checked pair collides when its coarse spheres come closer than the margin and so do its
fine (tight) spheres; both levels cover the same shapes, so this is the fine level's verdict,
reached the way the kernel reaches it.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.codes import SHAPE_CYLINDER, SHAPE_SPHERE
from kitchen_tamp.motion.geometry.spheres.scene import SphereScene

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]


def _world(link_poses: FloatArray, links: npt.NDArray[np.intp], centers: FloatArray) -> FloatArray:
    """(M, S, 3) world centres of spheres fixed on ``links``."""
    poses = link_poses[:, links]
    rotated: FloatArray = np.einsum("mskl,sl->msk", poses[:, :, :3, :3], centers)
    return rotated + poses[:, :, :3, 3]


def _box_gaps(
    points: FloatArray, rotation: FloatArray, center: FloatArray, half: FloatArray, kind: int
) -> FloatArray:
    """(M, S) signed distances from points (M, S, 3) to an obstacle (negative inside): an oriented
    box, a sphere or a cylinder (``kind``, `ObstacleBoxes.kinds`)."""
    if kind == SHAPE_SPHERE:
        sphere_gaps: FloatArray = np.linalg.norm(points - center, axis=-1) - half[0]
        return sphere_gaps
    local = (points - center) @ rotation
    if kind == SHAPE_CYLINDER:
        local = np.stack([np.linalg.norm(local[..., :2], axis=-1), local[..., 2]], axis=-1)
        half = half[[0, 2]]
    excess = np.abs(local) - half
    outside = np.linalg.norm(np.maximum(excess, 0.0), axis=-1)
    gaps: FloatArray = np.where(np.any(excess > 0.0, axis=-1), outside, np.max(excess, axis=-1))
    return gaps


def reference_validity(
    scene: SphereScene, qs: FloatArray, margin: float, lower: FloatArray, upper: FloatArray
) -> BoolArray:
    """Per row of ``qs``: within limits and no checked pair colliding at both levels."""
    batch = np.atleast_2d(np.asarray(qs, dtype=float))
    valid = np.all((batch >= lower - 1e-9) & (batch <= upper + 1e-9), axis=1)
    poses = scene.tree.link_poses(batch)
    coarse = _world(poses, scene.sphere_links, scene.sphere_centers)
    fine = _world(poses, scene.fine_links, scene.fine_centers)
    levels = ((coarse, scene.sphere_radii, "spheres"), (fine, scene.fine_radii, "fine_spheres"))
    boxes = scene.boxes
    for g, b in scene.group_box_pairs:
        hit = np.ones(len(batch), dtype=bool)
        for world, radii, field in levels:
            members = getattr(scene.groups[g], field)
            gaps = _box_gaps(
                world[:, members], boxes.rotations[b], boxes.centers[b], boxes.half_extents[b], boxes.kinds[b]
            )
            hit &= np.any(gaps - radii[members] < margin, axis=1)
        valid &= ~hit
    for g, h in scene.group_pairs:
        hit = np.ones(len(batch), dtype=bool)
        for world, radii, field in levels:
            first, second = getattr(scene.groups[g], field), getattr(scene.groups[h], field)
            distances = np.linalg.norm(world[:, first, None, :] - world[:, None, second, :], axis=-1)
            gaps = distances - radii[first][:, None] - radii[second][None, :]
            hit &= np.any(gaps < margin, axis=(1, 2))
        valid &= ~hit
    return np.asarray(valid, dtype=np.bool_)
