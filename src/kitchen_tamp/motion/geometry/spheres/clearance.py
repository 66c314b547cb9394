"""The sphere model's clearance for trajectory optimisation: one smooth value per configuration,
for many configurations per call, with its joint gradient.

``SphereClearance(scene, margin)(qs)`` answers ``(values (M,), gradients (M, n))`` where a value
is at least ``margin`` exactly when the smoothed penalty of `clearance_kernel` is within its
bound, i.e. when every checked sphere pair is at least its floor (``margin``) apart. It reads as a
distance: a single pair near contact gives a value that rises smoothly from ``margin`` (pair at
its floor) to ``margin + width`` (pair ``width`` further, or no pair that close), and pairs in
penetration push it below ``margin``. Several pairs near their floors at once count together,
which keeps the optimiser a little further from surfaces that many spheres face.

Conservative like the model: the spheres cover the links, so a configuration whose value is at
least ``margin`` keeps every checked pair of the exact geometry at least ``margin`` apart.

A move's fixed ends may be closer than the margin in the sphere model (the spheres overshoot the
links by up to about a centimetre, most between links 5 and 7, and a grasp or a drawer handle
puts the hand near contact), which would make the waypoints next to them infeasible. Given the
ends, a pair within the influence width of its floor at either end gets its floor lowered to a
width below its distance there: no pair adds to the penalty at the ends, which therefore have the
full clearance ``margin + width``, and the waypoints next to them are feasible. The exact
re-check of the path decides whether that was right.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.distances import SpherePairs, pair_distances
from kitchen_tamp.motion.geometry.spheres.kernels.loading import sphere_kernels
from kitchen_tamp.motion.geometry.spheres.scene import SphereScene

FloatArray = npt.NDArray[np.float64]

HINGE_AT_FLOOR = float(np.exp(-1.0))
"""The kernel's hinge ``phi(-1)`` (`kernels.clearance`): the penalty of one pair exactly at its floor,
the most the sum may reach."""
DEFAULT_INFLUENCE_WIDTH = 0.01
"""Pairs further than this (m) beyond their floor do not count (Drake's default influence offset)."""



def _offsets(sizes: list[int]) -> npt.NDArray[np.int64]:
    return np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64) if sizes else np.zeros(0, np.int64)


class SphereClearance:
    """Smooth clearance (m) of a sphere scene, batched, with analytic gradients."""

    def __init__(
        self,
        model: SphereScene,
        margin: float,
        width: float = DEFAULT_INFLUENCE_WIDTH,
        ends: FloatArray | None = None,
    ) -> None:
        if width <= 0.0:
            raise ValueError(f"influence width must be positive, got {width}")
        self.model = model
        self.margin = float(margin)
        self.width = float(width)
        self.pairs = SpherePairs.of(model)
        self.floors: FloatArray = np.full(len(self.pairs), self.margin)
        """Per pair of `SpherePairs` (its order), the distance (m) the pair must keep."""
        if ends is not None and len(self.pairs):
            at_ends = pair_distances(model, self.pairs, np.atleast_2d(np.asarray(ends, dtype=float)))
            self.floors = np.minimum(self.floors, at_ends.min(axis=0) - width)
        self.evaluations = 0
        """Configurations evaluated so far."""
        self._arguments = self._kernel_arrays()

    def _kernel_arrays(self) -> tuple[Any, ...]:
        model, layout = self.model, self.model.tree.flat_layout()
        sizes = [g.spheres.stop - g.spheres.start for g in model.groups]
        centers, radii = [], []
        for group in model.groups:
            local = model.sphere_centers[group.spheres]
            center = (local.min(axis=0) + local.max(axis=0)) / 2.0
            centers.append(center)
            radii.append(
                float(np.max(np.linalg.norm(local - center, axis=1) + model.sphere_radii[group.spheres]))
            )
        box_reach = np.einsum("bij,bj->bi", np.abs(model.boxes.rotations), model.boxes.half_extents)
        box_pairs, group_pairs = model.group_box_pairs, model.group_pairs
        box_sizes = [sizes[g] for g, _ in box_pairs]
        sphere_sizes = [sizes[g] * sizes[h] for g, h in group_pairs]
        sphere_offsets = _offsets(sphere_sizes) + sum(box_sizes)
        return (
            *layout.kernel_arrays(),
            np.ascontiguousarray(model.tree.depends),
            model.sphere_links.astype(np.int64),
            model.sphere_centers,
            model.sphere_radii,
            np.array([g.robot_link for g in model.groups], dtype=np.int64),
            np.array([g.spheres.start for g in model.groups], dtype=np.int64),
            np.array([g.spheres.stop for g in model.groups], dtype=np.int64),
            np.array(centers).reshape(-1, 3),
            np.array(radii),
            np.ascontiguousarray(model.boxes.rotations),
            np.ascontiguousarray(model.boxes.centers),
            np.ascontiguousarray(model.boxes.half_extents),
            model.boxes.centers - box_reach,
            model.boxes.centers + box_reach,
            box_pairs.astype(np.int64).reshape(-1, 2),
            _offsets(box_sizes),
            group_pairs.astype(np.int64).reshape(-1, 2),
            sphere_offsets.astype(np.int64),
        )

    def penalties(self, qs: FloatArray) -> tuple[FloatArray, FloatArray]:
        """The kernel's summed hinge penalties (M,) and their gradients (M, n)."""
        batch = np.ascontiguousarray(np.atleast_2d(np.asarray(qs, dtype=float)))
        self.evaluations += len(batch)
        kernel = sphere_kernels().clearance_penalties
        penalties, gradients = kernel(batch, self._arguments, self.floors, self.width)
        return np.asarray(penalties), np.asarray(gradients)

    def __call__(self, qs: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Clearance values (M,), at least ``margin`` when every pair keeps its floor, and their
        gradients (M, n)."""
        penalties, gradients = self.penalties(qs)
        scale = self.width / HINGE_AT_FLOOR
        return self.margin + self.width - scale * penalties, -scale * gradients
