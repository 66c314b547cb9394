"""Signed distances of the sphere model, per checked sphere pair, with analytic joint gradients.

Each checked pair is a sphere against an oriented box or against another
sphere. Its signed distance (m, negative when penetrating) is smooth in the
joints away from a box's edges and the sphere's centre crossing a box face's
medial planes, so a trajectory optimiser can constrain every pair on its own
instead of one minimum over all pairs (which kinks where the closest pair
changes). The gradient of a pair is ``n . (J_a - J_b)``: the unit direction of
separation times the difference of the two points' Jacobians
(`sphere_kinematics.point_jacobians`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kinematics import point_jacobians
from kitchen_tamp.motion.geometry.spheres.scene import SphereScene

FloatArray = npt.NDArray[np.float64]
IndexArray = npt.NDArray[np.intp]


@dataclass(frozen=True, eq=False)
class SpherePairs:
    """The checked pairs sphere by sphere: (sphere, box) and (sphere, sphere)."""

    box_spheres: IndexArray
    boxes: IndexArray
    first_spheres: IndexArray
    second_spheres: IndexArray

    @staticmethod
    def of(scene: SphereScene) -> SpherePairs:
        ranges = [np.arange(g.spheres.start, g.spheres.stop) for g in scene.groups]
        box_spheres = [ranges[g] for g, _ in scene.group_box_pairs]
        boxes = [np.full(len(ranges[g]), b) for g, b in scene.group_box_pairs]
        firsts = [np.repeat(ranges[g], len(ranges[h])) for g, h in scene.group_pairs]
        seconds = [np.tile(ranges[h], len(ranges[g])) for g, h in scene.group_pairs]

        def joined(parts: list[IndexArray]) -> IndexArray:
            return np.concatenate(parts).astype(np.intp) if parts else np.zeros(0, dtype=np.intp)

        return SpherePairs(joined(box_spheres), joined(boxes), joined(firsts), joined(seconds))

    def __len__(self) -> int:
        return len(self.box_spheres) + len(self.first_spheres)


def _box_offsets(
    scene: SphereScene, pairs: SpherePairs, centers: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Sphere centres in their boxes' frames (M, P, 3) and the boxes' half extents (P, 3)."""
    boxes = scene.boxes
    relative = centers[:, pairs.box_spheres] - boxes.centers[pairs.boxes]
    local = np.einsum("pji,mpj->mpi", boxes.rotations[pairs.boxes], relative)
    return local, boxes.half_extents[pairs.boxes]


def _box_signed_distances(local: FloatArray, half: FloatArray) -> FloatArray:
    excess = np.abs(local) - half
    outside = np.linalg.norm(np.maximum(excess, 0.0), axis=-1)
    signed: FloatArray = np.where(outside > 0.0, outside, np.max(excess, axis=-1))
    return signed


def pair_distances(scene: SphereScene, pairs: SpherePairs, qs: FloatArray) -> FloatArray:
    """(M, pairs) signed distances, sphere-box pairs first, for each row of ``qs``."""
    centers = scene.sphere_positions(scene.tree.link_poses(qs))
    local, half = _box_offsets(scene, pairs, centers)
    to_boxes = _box_signed_distances(local, half) - scene.sphere_radii[pairs.box_spheres]
    between = centers[:, pairs.first_spheres] - centers[:, pairs.second_spheres]
    to_spheres = np.linalg.norm(between, axis=-1) - scene.sphere_radii[pairs.first_spheres]
    to_spheres -= scene.sphere_radii[pairs.second_spheres]
    return np.concatenate([to_boxes, to_spheres], axis=1)


def _box_directions(local: FloatArray, half: FloatArray, rotations: FloatArray) -> FloatArray:
    """(P, 3) world unit gradients of each box's signed distance at the local points (P, 3)."""
    excess = np.abs(local) - half
    clipped = np.maximum(excess, 0.0) * np.sign(local)
    norm = np.linalg.norm(clipped, axis=-1, keepdims=True)
    deepest = np.argmax(excess, axis=-1)
    inside = np.zeros_like(local)
    inside[np.arange(len(local)), deepest] = np.sign(local[np.arange(len(local)), deepest])
    direction = np.where(norm > 0.0, clipped / np.where(norm > 0.0, norm, 1.0), inside)
    world: FloatArray = np.einsum("pij,pj->pi", rotations, direction)
    return world


def pair_distances_and_gradients(
    scene: SphereScene, pairs: SpherePairs, q: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Signed distances (pairs,) and their gradients (pairs, joints) at one configuration."""
    poses, frames = scene.tree.joint_axes(np.asarray(q, dtype=float)[None])
    centers = scene.sphere_positions(poses)
    jacobians = point_jacobians(centers, scene.sphere_links, scene.tree, frames)[0]  # (S, 3, n)
    local, half = _box_offsets(scene, pairs, centers)
    to_boxes = _box_signed_distances(local, half)[0] - scene.sphere_radii[pairs.box_spheres]
    directions = _box_directions(local[0], half, scene.boxes.rotations[pairs.boxes])
    box_gradients = np.einsum("pk,pkn->pn", directions, jacobians[pairs.box_spheres])
    between = centers[0, pairs.first_spheres] - centers[0, pairs.second_spheres]
    lengths = np.linalg.norm(between, axis=-1)
    to_spheres = lengths - scene.sphere_radii[pairs.first_spheres] - scene.sphere_radii[pairs.second_spheres]
    units = between / np.maximum(lengths, 1e-12)[:, None]
    relative = jacobians[pairs.first_spheres] - jacobians[pairs.second_spheres]
    sphere_gradients = np.einsum("pk,pkn->pn", units, relative)
    return np.concatenate([to_boxes, to_spheres]), np.concatenate([box_gradients, sphere_gradients])
