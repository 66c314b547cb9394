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
    from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker


class ExactModel(CollisionChecker, Protocol):
    """An exact collision model that also measures signed distance (Drake's)."""

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]: ...


Exact = TypeVar("Exact", bound=CollisionChecker)

REMEMBERED_VERDICTS = 256
"""Exact verdicts a screened checker remembers, by configuration (oldest forgotten first): a move's
start and goal are asked about again and again (before planning, by the planner, by the dense
post-check), and near contact the spheres reject them every time."""


class SphereScreenedChecker(Generic[Exact]):
    """``spheres`` first; the configurations they reject are checked again by ``exact``, which
    (when it measures distance) also answers distance queries, so trajectory optimisation
    sees the exact model."""

    def __init__(self, spheres: SphereCollisionChecker, exact: Exact, *, exact_is_bare: bool = False) -> None:
        self.spheres = spheres
        self.exact = exact
        self.exact_is_bare = exact_is_bare
        """Whether ``exact`` measures the bare collision hulls (Drake; not PyBullet, whose meshes carry
        a margin): then a row the spheres reject only by their mesh padding is valid without asking."""
        self.lower: JointConfiguration = spheres.lower
        self.upper: JointConfiguration = spheres.upper
        self.exact_checks = 0
        """Configurations handed to the exact model so far."""
        self.exact_seconds = 0.0
        """Wall-clock seconds the exact model took so far."""
        self._segments = CountingSegmentChecker(self, spheres.segment_resolution)
        self._verdicts: dict[bytes, bool] = {}

    def _exact_verdicts(self, qs: JointConfigurations) -> ValidityMask:
        """The exact model's verdicts on the rows of ``qs``; remembered ones are not asked again."""
        if self.exact_is_bare:
            bare = self.spheres.is_valid_without_padding(qs)
            if bare.any():
                verdicts = bare.copy()
                verdicts[~bare] = self._exact_verdicts_asked(qs[~bare])
                return verdicts
        return self._exact_verdicts_asked(qs)

    def _exact_verdicts_asked(self, qs: JointConfigurations) -> ValidityMask:
        keys = [q.tobytes() for q in qs]
        verdicts = [self._verdicts.get(key) for key in keys]
        unknown = [row for row, verdict in enumerate(verdicts) if verdict is None]
        if unknown:
            clock = time.perf_counter()
            self.exact_checks += len(unknown)
            answers = self.exact.is_valid(qs[unknown])
            self.exact_seconds += time.perf_counter() - clock
            for row, answer in zip(unknown, answers.tolist(), strict=True):
                verdicts[row] = bool(answer)
                self._remember(keys[row], bool(answer))
        return np.array(verdicts, dtype=np.bool_)

    def _remember(self, key: bytes, verdict: bool) -> None:
        if len(self._verdicts) >= REMEMBERED_VERDICTS:
            del self._verdicts[next(iter(self._verdicts))]
        self._verdicts[key] = verdict

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = self.spheres.is_valid(batch)
        rejected = np.flatnonzero(~valid)
        if len(rejected):
            valid[rejected] = self._exact_verdicts(batch[rejected])
        return valid

    def first_invalid(self, qs: JointConfigurations) -> int | None:
        """Index of the first invalid row, or None: the exact model is asked about the rows the
        spheres reject in order, stopping at the first it confirms (segment checks need no more)."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = self.spheres.is_valid(batch)
        if valid.all():
            return None
        rejected = np.flatnonzero(~valid)
        if self.exact_is_bare:
            rejected = rejected[~self.spheres.is_valid_without_padding(batch[rejected])]
        for index in rejected.tolist():
            if not self._exact_valid(batch[index]):
                return int(index)
        return None

    def _exact_valid(self, q: JointConfiguration) -> bool:
        """The exact model's verdict on one configuration, remembered."""
        key = q.tobytes()
        verdict = self._verdicts.get(key)
        if verdict is None:
            clock = time.perf_counter()
            self.exact_checks += 1
            verdict = bool(self.exact.is_valid(q[np.newaxis])[0])
            self.exact_seconds += time.perf_counter() - clock
            self._remember(key, verdict)
        return verdict

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return self._segments.segment_valid(np.asarray(q0, dtype=float), np.asarray(q1, dtype=float))

    def signed_distance(
        self: SphereScreenedChecker[ExactModel], q: JointConfiguration
    ) -> tuple[float, JointConfiguration]:
        """The exact model's minimum signed distance and its gradient."""
        return self.exact.signed_distance(q)
