"""A conservative model in front of an exact one: the sphere model accepts, the exact model decides
what the spheres reject.

The spheres cover the links, so a configuration they find clear is clear for
the exact model too; only the configurations they reject (truly colliding, or
within the spheres' overshoot of contact) are asked again. Verdicts are the
exact model's; most configurations never reach it.

The exact model can be Drake's (planning: it also answers distance queries) or
the simulator's own PyBullet checker (the dense post-check of a planned path),
as long as the spheres model the same scene with the same margin.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Generic, Protocol, TypeVar

import numpy as np

from kitchen_tamp.motion.collision_checker import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    ValidityMask,
)
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker

if TYPE_CHECKING:  # the real import loads numba; a screened checker is only built from a sphere model
    from kitchen_tamp.motion.sphere_checker import SphereCollisionChecker


class ExactModel(CollisionChecker, Protocol):
    """An exact collision model that also measures signed distance (Drake's)."""

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]: ...


Exact = TypeVar("Exact", bound=CollisionChecker)


class SphereScreenedChecker(Generic[Exact]):
    """``spheres`` first; the configurations they reject are checked again by ``exact``, which
    (when it measures distance) also answers distance queries, so trajectory optimisation
    sees the exact model."""

    def __init__(self, spheres: SphereCollisionChecker, exact: Exact) -> None:
        self.spheres = spheres
        self.exact = exact
        self.lower: JointConfiguration = spheres.lower
        self.upper: JointConfiguration = spheres.upper
        self.exact_checks = 0
        """Configurations handed to the exact model so far."""
        self.exact_seconds = 0.0
        """Wall-clock seconds the exact model took so far."""
        self._segments = CountingSegmentChecker(self, spheres.segment_resolution)

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = self.spheres.is_valid(batch)
        rejected = np.flatnonzero(~valid)
        if len(rejected):
            clock = time.perf_counter()
            self.exact_checks += len(rejected)
            valid[rejected] = self.exact.is_valid(batch[rejected])
            self.exact_seconds += time.perf_counter() - clock
        return valid

    def first_invalid(self, qs: JointConfigurations) -> int | None:
        """Index of the first invalid row, or None: the exact model is asked about the rows the
        spheres reject in order, stopping at the first it confirms (segment checks need no more)."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        rejected = np.flatnonzero(~self.spheres.is_valid(batch))
        if len(rejected) == 0:
            return None
        clock = time.perf_counter()
        try:
            for index in rejected:
                self.exact_checks += 1
                if not self.exact.is_valid(batch[index : index + 1])[0]:
                    return int(index)
            return None
        finally:
            self.exact_seconds += time.perf_counter() - clock

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return self._segments.segment_valid(np.asarray(q0, dtype=float), np.asarray(q1, dtype=float))

    def signed_distance(
        self: SphereScreenedChecker[ExactModel], q: JointConfiguration
    ) -> tuple[float, JointConfiguration]:
        """The exact model's minimum signed distance and its gradient."""
        return self.exact.signed_distance(q)
