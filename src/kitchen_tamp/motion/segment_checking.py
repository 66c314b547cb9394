"""Segment checks built from batched configuration checks, counted.

A straight joint-space segment is checked at the states ``kitchen_tamp.joint_spacing``
defines (the rule every checker and the judge share), endpoints first, then
interior points from coarse to fine in growing batches, stopping at the first
collision. A checker that can stop inside a batch at its first colliding
configuration (`FirstCollisionFinder`, e.g. one whose exact model is slow) is
asked for that instead of every configuration's verdict.
"""

from __future__ import annotations

import functools
import math
from typing import Any, Protocol, runtime_checkable

import numpy as np
import numpy.typing as npt

from kitchen_tamp.joint_spacing import coarse_to_fine_order, interior_fractions, interval_count
from kitchen_tamp.motion.collision_checker import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    ValidityMask,
)

FIRST_BATCH_SIZE = 16
"""Interior configurations checked in the first batch; later batches double."""


@functools.lru_cache(maxsize=4096)
def _batches(count: int) -> tuple[slice, ...]:
    batches = []
    start, size = 0, FIRST_BATCH_SIZE
    while start < count:
        batches.append(slice(start, min(count, start + size)))
        start, size = start + size, size * 2
    return tuple(batches)


def raked_order(count: int, block: int) -> npt.NDArray[np.intp]:
    """The order a free prefix's ``count`` configurations are visited in: block by block from the
    near end, ``block`` configurations each, each block's last first, then its others coarse to
    fine (a colliding block is usually found out within its first few). One configuration a
    block visits them outward."""
    order = np.empty(count, dtype=np.intp)
    row = 0
    for start in range(0, count, block):
        stop = min(count, start + block)
        order[row] = stop - 1
        interior = stop - start - 1
        order[row + 1 : row + 1 + interior] = start + coarse_to_fine_order(interior)
        row += 1 + interior
    return order


def prefix_lengths(distance: float, resolution: float) -> npt.NDArray[np.float64]:
    """How far from its start each configuration of a free prefix ``distance`` long lies: every
    multiple of ``resolution`` short of ``distance``, then ``distance`` itself."""
    lengths = np.append(np.arange(1, math.ceil(distance / resolution)), distance / resolution)
    return np.asarray(lengths * resolution, dtype=np.float64)


def blocks_free_length(lengths: npt.NDArray[np.float64], first_invalid: int, block: int) -> float:
    """How far is free in whole blocks when ``lengths``' configuration ``first_invalid`` is the
    nearest colliding one: the end of the last block before the one holding it."""
    free_blocks = first_invalid // block
    return float(lengths[free_blocks * block - 1]) if free_blocks else 0.0


@runtime_checkable
class FirstCollisionFinder(Protocol):
    """A checker that finds the first colliding row of a batch without deciding the rows after it."""

    def first_invalid(self, qs: JointConfigurations) -> int | None:
        """Index of the first row of ``qs`` (n, d) that is not valid, or None when all are."""
        ...


@runtime_checkable
class CompiledSegments(Protocol):
    """A checker that checks a whole segment in one call (a compiled model): the configurations
    `CountingSegmentChecker` would check, in its order, with its verdict and its count."""

    def segment_checked(
        self,
        q0: JointConfiguration,
        q1: JointConfiguration,
        intervals: int,
        check_start: bool,
        check_end: bool,
    ) -> tuple[bool, int]:
        """(whether q0 -> q1 cut into ``intervals`` is valid, configurations counted)."""
        ...

    def free_prefix_checked(
        self, q0: JointConfiguration, q1: JointConfiguration, distance: float, resolution: float, block: int
    ) -> tuple[float, int]:
        """(the free length from q0 toward q1 in whole blocks, configurations counted), as
        `CountingSegmentChecker.free_prefix_length`."""
        ...


@runtime_checkable
class CompiledValidity(Protocol):
    """A checker whose every verdict a compiled loop can reach without Python: the sphere model's
    validity arrays and margin, for `sphere_segments`' kernels (the compiled RRT-Connect loop)."""

    def compiled_validity(self) -> tuple[Any, float] | None:
        """(the model's `ValidityArrays`, the margin), or None when some verdict needs Python
        (an exact model deciding near an end)."""
        ...


class CountingSegmentChecker:
    """Wraps a `CollisionChecker`: segment checks at a resolution, and a count of checks."""

    def __init__(self, checker: CollisionChecker, resolution: float) -> None:
        if resolution <= 0.0:
            raise ValueError(f"resolution must be positive, got {resolution}")
        self.checker = checker
        self.resolution = resolution
        self.configurations_checked = 0
        self._finder = checker if isinstance(checker, FirstCollisionFinder) else None
        self._compiled = checker if isinstance(checker, CompiledSegments) else None

    def are_valid(self, qs: JointConfigurations) -> ValidityMask:
        """Check a batch of configurations, shape (n, d), counting each."""
        self.configurations_checked += len(qs)
        return np.asarray(self.checker.is_valid(qs), dtype=np.bool_)

    def first_invalid(self, qs: JointConfigurations) -> int | None:
        """Index of the first invalid row of a batch (n, d), or None; counts each row, as the
        rows after the first collision would have been checked by ``are_valid``."""
        if self._finder is not None:
            self.configurations_checked += len(qs)
            return self._finder.first_invalid(qs)
        valid = self.are_valid(qs)
        return None if bool(np.all(valid)) else int(np.argmin(valid))

    def is_valid(self, q: JointConfiguration) -> bool:
        """Check one configuration."""
        return bool(self.are_valid(q[np.newaxis])[0])

    def segment_valid(
        self,
        q0: JointConfiguration,
        q1: JointConfiguration,
        *,
        check_start: bool = True,
        check_end: bool = True,
    ) -> bool:
        """Whether the straight segment q0 -> q1 is collision-free at the resolution.

        Endpoints are checked first (fail fast), except those the caller
        vouches for with `check_start=False` / `check_end=False`.
        """
        endpoints = [q for q, check in ((q0, check_start), (q1, check_end)) if check]
        if self._compiled is not None:
            intervals = interval_count(q0, q1, self.resolution)
            free, checked = self._compiled.segment_checked(q0, q1, intervals, check_start, check_end)
            self.configurations_checked += checked
            return free
        fractions = interior_fractions(q0, q1, self.resolution)
        if endpoints and self.first_invalid(np.stack(endpoints)) is not None:
            return False
        for batch in _batches(len(fractions)):
            qs = q0 + fractions[batch, np.newaxis] * (q1 - q0)
            if self.first_invalid(qs) is not None:
                return False
        return True

    def free_prefix_length(self, q0: JointConfiguration, q1: JointConfiguration, block: int = 1) -> float:
        """How far from q0 toward q1 one can go before the first collision, in whole blocks.

        `q0` is assumed valid. The configurations lie exactly `resolution` apart from q0 (then q1
        itself), so any prefix ending at a multiple of `resolution` has been checked on the same
        points `segment_valid` would use for it. They are visited block by block, ``block`` of them
        each (`raked_order`). Returns the full distance when q1 is reached, else the end of the
        last block before the one holding the nearest collision (with blocks of one, the last
        free multiple of `resolution`).
        """
        distance = float(np.linalg.norm(q1 - q0))
        if distance == 0.0:
            return 0.0
        if self._compiled is not None:
            length, checked = self._compiled.free_prefix_checked(q0, q1, distance, self.resolution, block)
            self.configurations_checked += checked
            return length
        lengths = prefix_lengths(distance, self.resolution)
        order = raked_order(len(lengths), block)
        for batch in _batches(len(lengths)):
            qs = q0 + (lengths[order[batch], np.newaxis] / distance) * (q1 - q0)
            first_in_batch = self.first_invalid(qs)
            if first_in_batch is not None:
                return blocks_free_length(lengths, int(order[batch.start + first_in_batch]), block)
        return distance
