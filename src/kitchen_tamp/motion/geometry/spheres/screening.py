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
from collections.abc import Sequence
from typing import TYPE_CHECKING, Generic, Protocol, TypeVar

import numpy as np

from kitchen_tamp.motion.collision_checker import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    ValidityMask,
)
from kitchen_tamp.motion.segment_checking import (
    CountingSegmentChecker,
    blocks_free_length,
    prefix_lengths,
)

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

    def exact_verdicts(self, qs: JointConfigurations) -> ValidityMask:
        """The exact model's verdicts on rows the spheres rejected (rows the bare spheres clear are
        valid without asking when ``exact_is_bare``); remembered ones are not asked again."""
        return self._exact_verdicts(np.atleast_2d(np.asarray(qs, dtype=float)))

    def exact_valid(self, q: JointConfiguration) -> bool:
        """The exact model's verdict on one configuration the spheres rejected (as ``exact_verdicts``)."""
        return bool(self.exact_verdicts(q)[0])

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


DEFAULT_END_REACH = 0.2
"""How far (rad, joint-space Euclidean) from an end the spheres reject an `EndConfirmedChecker` asks
the exact model about their rejections: far enough to leave the few millimetres of the spheres'
overshoot in most directions (0.2 rad moves the hand by centimetres)."""


class EndConfirmedChecker(Generic[Exact]):
    """The sphere model, compiled segments and all, except near a given end (a query's start or goal)
    the spheres reject but ``exact`` accepts: there the spheres' rejections are confirmed by ``exact``.

    An end within the spheres' overshoot of an obstacle (millimetres from it for the exact model)
    would make the sphere model refuse the query, and every move out of it; the exact model
    decides near such an end and the spheres everywhere else. Ends the spheres accept add nothing,
    so a query with free ends is checked by the spheres alone, at their speed."""

    def __init__(
        self,
        spheres: SphereCollisionChecker,
        exact: Exact,
        ends: Sequence[JointConfiguration],
        reach: float = DEFAULT_END_REACH,
        *,
        exact_is_bare: bool = False,
    ) -> None:
        self.spheres = spheres
        self.screened = SphereScreenedChecker(spheres, exact, exact_is_bare=exact_is_bare)
        self.reach = float(reach)
        self.lower: JointConfiguration = spheres.lower
        self.upper: JointConfiguration = spheres.upper
        self.segment_resolution = spheres.segment_resolution
        candidates = np.atleast_2d(np.asarray(ends, dtype=float)).reshape(-1, len(self.lower))
        rejected = candidates[~spheres.is_valid(candidates)] if len(candidates) else candidates
        confirmed = self.screened.exact_verdicts(rejected) if len(rejected) else np.zeros(0, dtype=np.bool_)
        self.ends: JointConfigurations = rejected[confirmed]
        """The ends the spheres reject and the exact model accepts: where the exact model decides."""
        self._segments = CountingSegmentChecker(self, spheres.segment_resolution)

    def compiled_validity(self) -> tuple[object, float] | None:
        """`CompiledValidity`: the spheres' when no end needs the exact model, else None."""
        return self.spheres.compiled_validity() if len(self.ends) == 0 else None

    def _near_ends(self, qs: JointConfigurations) -> ValidityMask:
        """Per row of ``qs``: whether it lies within ``reach`` of one of ``ends``."""
        gaps = np.linalg.norm(qs[:, np.newaxis, :] - self.ends[np.newaxis], axis=2)
        return np.asarray(np.any(gaps <= self.reach, axis=1), dtype=np.bool_)

    def _segment_nears_ends(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        """Whether the straight segment q0 -> q1 passes within ``reach`` of one of ``ends``."""
        if len(self.ends) == 0:
            return False
        step = q1 - q0
        squared = float(step @ step)
        along = (
            np.clip((self.ends - q0) @ step / squared, 0.0, 1.0)
            if squared > 0.0
            else np.zeros(len(self.ends))
        )
        closest = q0 + along[:, np.newaxis] * step
        return bool(np.any(np.linalg.norm(self.ends - closest, axis=1) <= self.reach))

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = self.spheres.is_valid(batch)
        if len(self.ends) and not valid.all():
            asked = np.flatnonzero(~valid)
            asked = asked[self._near_ends(batch[asked])]
            if len(asked):
                valid[asked] = self.screened.exact_verdicts(batch[asked])
        return valid

    def first_invalid(self, qs: JointConfigurations) -> int | None:
        """Index of the first invalid row, or None; the exact model is asked in order about the
        rejected rows near an end, up to the first rejection it confirms or that is not near one."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = self.spheres.is_valid(batch)
        rejected = np.flatnonzero(~valid)
        if len(rejected) == 0:
            return None
        if len(self.ends) == 0:
            return int(rejected[0])
        near = self._near_ends(batch[rejected])
        for index, is_near in zip(rejected.tolist(), near.tolist(), strict=True):
            if not is_near or not self.screened.exact_valid(batch[index]):
                return int(index)
        return None

    def segment_checked(
        self,
        q0: JointConfiguration,
        q1: JointConfiguration,
        intervals: int,
        check_start: bool,
        check_end: bool,
    ) -> tuple[bool, int]:
        """`CompiledSegments.segment_checked`: the spheres' compiled check, and where they reject a
        segment near an end, its states again with the exact model deciding near the end."""
        free, checked = self.spheres.segment_checked(q0, q1, intervals, check_start, check_end)
        if free or not self._segment_nears_ends(q0, q1):
            return free, checked
        fractions = np.arange(0 if check_start else 1, intervals + 1 if check_end else intervals) / intervals
        states = q0 + fractions[:, np.newaxis] * (q1 - q0)
        return self.first_invalid(states) is None, checked + len(states)

    def free_prefix_checked(
        self, q0: JointConfiguration, q1: JointConfiguration, distance: float, resolution: float, block: int
    ) -> tuple[float, int]:
        """`CompiledSegments.free_prefix_checked`, with the exact model deciding near an end."""
        length, checked = self.spheres.free_prefix_checked(q0, q1, distance, resolution, block)
        if length >= distance or not self._segment_nears_ends(q0, q1):
            return length, checked
        lengths = prefix_lengths(distance, resolution)
        first = self.first_invalid(q0 + (lengths[:, np.newaxis] / distance) * (q1 - q0))
        if first is None:
            return distance, checked + len(lengths)
        return blocks_free_length(lengths, first, block), checked + len(lengths)

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return self._segments.segment_valid(np.asarray(q0, dtype=float), np.asarray(q1, dtype=float))
