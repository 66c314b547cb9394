"""Post-check of any joint path (planned or optimised): dense collision checking."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.motion.collision_checker import CollisionChecker
from kitchen_tamp.motion.joint_path import JointPath, densify_path


@dataclass(frozen=True)
class PathCheck:
    """Outcome of `check_path_densely`.

    `first_collision` is the index, in the densified path, of the first
    colliding configuration (None when free); `first_colliding_segment` the
    index of the original segment it lies on (0 for a colliding start).
    """

    collision_free: bool
    configurations_checked: int
    first_collision: int | None
    first_colliding_segment: int | None


def check_path_densely(path: JointPath, checker: CollisionChecker, resolution: float) -> PathCheck:
    """Check every waypoint and points between them at most `resolution` apart, in one batch."""
    if path.ndim != 2 or len(path) == 0:
        raise ValueError(f"a path is a non-empty (m, d) array, got shape {path.shape}")
    dense = densify_path(path, resolution)
    valid = np.asarray(checker.is_valid(dense), dtype=np.bool_)
    if np.all(valid):
        return PathCheck(True, len(dense), None, None)
    first = int(np.argmin(valid))
    steps = np.linalg.norm(np.diff(path, axis=0), axis=1)
    dense_per_segment = np.maximum(1, np.ceil(steps / resolution)).astype(int)
    segment_end_rows = np.cumsum(dense_per_segment)
    segment = int(np.searchsorted(segment_end_rows, first)) if first > 0 else 0
    return PathCheck(False, len(dense), first, segment)
