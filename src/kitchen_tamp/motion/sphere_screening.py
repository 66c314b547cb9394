"""A conservative model in front of an exact one: the sphere model accepts, the exact model decides
what the spheres reject.

The spheres cover the links, so a configuration they find clear is clear for
the exact model too; only the configurations they reject (truly colliding, or
within the spheres' overshoot of contact) are asked again. Verdicts are the
exact model's; most configurations never reach it.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from kitchen_tamp.motion.collision_checker import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    ValidityMask,
)
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker
from kitchen_tamp.motion.sphere_checker import SphereCollisionChecker


class ExactModel(CollisionChecker, Protocol):
    """An exact collision model that also measures signed distance (Drake's)."""

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]: ...


class SphereScreenedChecker:
    """``spheres`` first; the configurations they reject are checked again by ``exact``, which
    also answers distance queries (so trajectory optimisation sees the exact model)."""

    def __init__(self, spheres: SphereCollisionChecker, exact: ExactModel) -> None:
        self.spheres = spheres
        self.exact = exact
        self.lower: JointConfiguration = spheres.lower
        self.upper: JointConfiguration = spheres.upper
        self.exact_checks = 0
        """Configurations handed to the exact model so far."""
        self._segments = CountingSegmentChecker(self, spheres.segment_resolution)

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = self.spheres.is_valid(batch)
        rejected = np.flatnonzero(~valid)
        if len(rejected):
            self.exact_checks += len(rejected)
            valid[rejected] = self.exact.is_valid(batch[rejected])
        return valid

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return self._segments.segment_valid(np.asarray(q0, dtype=float), np.asarray(q1, dtype=float))

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]:
        """The exact model's minimum signed distance and its gradient."""
        return self.exact.signed_distance(q)
