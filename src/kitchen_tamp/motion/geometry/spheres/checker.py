"""The sphere model as a collision checker: batched validity, segments, signed distances.

`SphereCollisionChecker` is a `CollisionChecker` with joint limits (what the
kitchen's motion back ends take) built from a scene description. A batch of
configurations is checked by one compiled call (`sphere_kernels`); segments are
checked coarse to fine in growing batches, stopping at the first colliding
batch (`CountingSegmentChecker`). ``min_distance`` and ``signed_distance`` have
the Drake checker's meaning (minimum over checked pairs, capped at the
horizon); ``pair_distances`` gives every pair with its gradient
(`sphere_distances`).

The model is conservative: the spheres cover the links' collision hulls (and
PyBullet's margin around them), obstacles are boxes, so what PyBullet finds
colliding the model finds colliding; the reverse may not hold near contact.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.joint_spacing import PLANNING_RESOLUTION_RAD
from kitchen_tamp.motion.collision_checker import JointConfiguration, JointConfigurations, ValidityMask
from kitchen_tamp.motion.geometry.described_scene import DEFAULT_DISTANCE_HORIZON, DescribedScene
from kitchen_tamp.motion.geometry.spheres.covering import DEFAULT_COVERING_TOLERANCE
from kitchen_tamp.motion.geometry.spheres.distances import (
    SpherePairs,
    pair_distances,
    pair_distances_and_gradients,
)
from kitchen_tamp.motion.geometry.spheres.kernels.layout import kernel_arguments, with_pair_tables
from kitchen_tamp.motion.geometry.spheres.kernels.loading import PackedValidity, sphere_kernels
from kitchen_tamp.motion.geometry.spheres.pair_tables import pair_tables
from kitchen_tamp.motion.geometry.spheres.reference import reference_validity
from kitchen_tamp.motion.geometry.spheres.scene import PYBULLET_MESH_MARGIN, SphereScene
from kitchen_tamp.motion.geometry.urdf import read_urdf
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker

if TYPE_CHECKING:  # the real import loads numba, which a run served ahead of time never needs
    from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import ValidityArrays

FloatArray = npt.NDArray[np.float64]


class SphereCollisionChecker:
    """Batch validity and signed distances of arm configurations against a sphere model.

    Valid: within the arm's limits and no checked pair closer than ``margin`` (m).
    """

    def __init__(
        self,
        scene: DescribedScene,
        margin: float = 0.0,
        distance_horizon: float = DEFAULT_DISTANCE_HORIZON,
        segment_resolution: float = PLANNING_RESOLUTION_RAD,
        tolerance: float = DEFAULT_COVERING_TOLERANCE,
        mesh_padding: float = PYBULLET_MESH_MARGIN,
    ) -> None:
        self.margin = float(margin)
        self.distance_horizon = float(distance_horizon)
        self.model = SphereScene(scene, tolerance, mesh_padding)
        self.lower: FloatArray = self.model.arm_lower
        self.upper: FloatArray = self.model.arm_upper
        self.pairs = SpherePairs.of(self.model)
        self.segment_resolution = float(segment_resolution)
        self._segments = CountingSegmentChecker(self, segment_resolution)
        self._kernel_arguments = self._arrays()
        self._kernels = sphere_kernels()
        self._packed = self._kernels.pack(self._kernel_arguments)
        self._jit_packed: ValidityArrays | None = None
        self.padding = self._padding_per_group(scene, mesh_padding)
        """(groups,) how much each group's spheres were padded beyond its collision hulls (m): the mesh
        margin PyBullet adds and a model of the bare hulls (Drake's) does not."""
        self._unpadded = self._unpadded_passes()

    def _padding_per_group(self, scene: DescribedScene, mesh_padding: float) -> FloatArray:
        """A robot link covered only by meshes is padded by ``mesh_padding`` (as `SphereScene` pads
        them); boxes and carried bodies are not padded."""
        robot = next(b for b in scene.bodies if b.name == scene.robot)
        kinds: dict[str, set[str]] = {}
        for shape in read_urdf(robot.urdf_path).collisions:
            kinds.setdefault(shape.link, set()).add(shape.kind)
        return np.array(
            [
                mesh_padding if group.role != "carried" and kinds.get(group.link) == {"mesh"} else 0.0
                for group in self.model.groups
            ],
            dtype=float,
        )

    def with_margin(self, margin: float) -> SphereCollisionChecker:
        """The same model keeping ``margin`` instead (sharing the scene and the kernel's arrays)."""
        twin = copy.copy(self)
        twin.margin = float(margin)
        twin._segments = CountingSegmentChecker(twin, self.segment_resolution)
        return twin

    @property
    def kernel_arguments(self) -> tuple[Any, ...]:
        """The validity kernel's arrays, in `validity_fields.VALIDITY_FIELDS` order."""
        return self._kernel_arguments

    def _arrays(self) -> tuple[Any, ...]:
        """The kernel's arguments, with tables proved at this checker's margin for the self pairs
        two joints place (`sphere_pair_tables`)."""
        plain = kernel_arguments(self.model, self.lower, self.upper)
        return with_pair_tables(plain, pair_tables(self.model, plain, self.margin))

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        """Per row of ``qs`` (n, 7): within the arm's limits and no checked pair closer than the margin."""
        batch = np.ascontiguousarray(np.atleast_2d(np.asarray(qs, dtype=float)))
        valid = self._kernels.valid(batch, self._packed, self.margin, False)
        return np.asarray(valid, dtype=np.bool_)

    def first_invalid(self, qs: JointConfigurations) -> int | None:
        """Index of the first row of ``qs`` (n, 7) that is not valid, or None; the rows after it
        are not checked (a `FirstCollisionFinder`)."""
        batch = np.ascontiguousarray(np.atleast_2d(np.asarray(qs, dtype=float)))
        if len(batch) == 0:
            return None
        valid = self._kernels.valid(batch, self._packed, self.margin, True)
        first = int(np.argmin(valid))
        return None if valid[first] else first

    def compiled_validity(self) -> tuple[ValidityArrays, float]:
        """`CompiledValidity`: the packed kernel arrays and the margin (every verdict is compiled), as
        the JIT kernels take them (packed on first use: a kitchen run never asks)."""
        if self._jit_packed is None:
            from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import validity_arrays

            self._jit_packed = validity_arrays(self._kernel_arguments)
        return self._jit_packed, self.margin

    def segment_checked(
        self,
        q0: JointConfiguration,
        q1: JointConfiguration,
        intervals: int,
        check_start: bool,
        check_end: bool,
    ) -> tuple[bool, int]:
        """`CompiledSegments.segment_checked` in one compiled call (`sphere_segments`)."""
        from kitchen_tamp.motion.geometry.spheres.kernels.segments import segment_checked

        start, end = np.ascontiguousarray(q0, dtype=float), np.ascontiguousarray(q1, dtype=float)
        arrays, margin = self.compiled_validity()
        kernel: Any = segment_checked  # numba's dispatcher stubs take no argument list
        free, checked = kernel(start, end, intervals, check_start, check_end, arrays, margin)
        return bool(free), int(checked)

    def free_prefix_checked(
        self, q0: JointConfiguration, q1: JointConfiguration, distance: float, resolution: float, block: int
    ) -> tuple[float, int]:
        """`CompiledSegments.free_prefix_checked` in one compiled call (`sphere_segments`)."""
        from kitchen_tamp.motion.geometry.spheres.kernels.segments import free_prefix_checked

        start, end = np.ascontiguousarray(q0, dtype=float), np.ascontiguousarray(q1, dtype=float)
        arrays, margin = self.compiled_validity()
        kernel: Any = free_prefix_checked  # numba's dispatcher stubs take no argument list
        length, checked = kernel(start, end, distance, resolution, block, arrays, margin)
        return float(length), int(checked)

    def is_valid_without_padding(self, qs: JointConfigurations) -> ValidityMask:
        """``is_valid`` with each pair's margin lowered by its groups' padding: the verdict of the
        spheres covering the bare collision hulls, so a row found valid here is clear of the margin
        for a model of the bare meshes (Drake's), though PyBullet (whose distances include the
        mesh margin) may find it closer."""
        batch = np.ascontiguousarray(np.atleast_2d(np.asarray(qs, dtype=float)))
        valid = np.ones(len(batch), dtype=np.bool_)
        for offset, arguments in self._unpadded:
            rows = np.flatnonzero(valid)
            if len(rows) == 0:
                break
            valid[rows] = self._kernels.valid(batch[rows], arguments, self.margin - offset, False)
        return valid

    def _unpadded_passes(self) -> list[tuple[float, PackedValidity]]:
        """Kernel arguments per margin offset, each with the pairs whose padding sums to it."""
        *shared, box_pairs, group_pairs = self._kernel_arguments
        box_offsets = self.padding[box_pairs[:, 0]]
        pair_offsets = self.padding[group_pairs[:, 0]] + self.padding[group_pairs[:, 1]]
        passes = []
        for offset in sorted(set(box_offsets.tolist()) | set(pair_offsets.tolist())):
            boxes = np.ascontiguousarray(box_pairs[box_offsets == offset])
            groups = np.ascontiguousarray(group_pairs[pair_offsets == offset])
            passes.append((offset, self._kernels.pack((*shared, boxes, groups))))
        return passes

    def is_valid_uncompiled(self, qs: JointConfigurations) -> ValidityMask:
        """The same verdicts as ``is_valid`` from every pair's spheres in numpy (a reference)."""
        return reference_validity(
            self.model, np.asarray(qs, dtype=float), self.margin, self.lower, self.upper
        )

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        """Whether the straight segment is valid, checked at the checker's resolution."""
        return self._segments.segment_valid(np.asarray(q0, dtype=float), np.asarray(q1, dtype=float))

    def pair_distances(self, q: JointConfiguration) -> tuple[FloatArray, FloatArray]:
        """Every checked pair's signed distance (pairs,) and gradient (pairs, 7) at ``q``."""
        return pair_distances_and_gradients(self.model, self.pairs, np.asarray(q, dtype=float))

    def min_distance(self, q: JointConfiguration) -> float:
        """Smallest signed distance (m) over the checked pairs, capped at ``distance_horizon``."""
        distances = pair_distances(self.model, self.pairs, np.asarray(q, dtype=float)[None])[0]
        return float(min(np.min(distances, initial=self.distance_horizon), self.distance_horizon))

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]:
        """(``min_distance(q)``, its gradient); zero gradient beyond the horizon."""
        distances, gradients = self.pair_distances(q)
        if len(distances) == 0 or np.min(distances) >= self.distance_horizon:
            return self.distance_horizon, np.zeros(len(self.lower))
        closest = int(np.argmin(distances))
        return float(distances[closest]), gradients[closest]
