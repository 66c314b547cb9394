"""Joint-space paths as (m, d) arrays: length, densification and resampling."""

from __future__ import annotations

import itertools

import numpy as np
import numpy.typing as npt

JointPath = npt.NDArray[np.float64]
"""A piecewise-linear joint-space path: waypoints as rows, shape (m, d), m >= 1."""


def segment_lengths(path: JointPath) -> npt.NDArray[np.float64]:
    """Euclidean joint-space length of each of the m - 1 segments."""
    return np.asarray(np.linalg.norm(np.diff(path, axis=0), axis=1), dtype=np.float64)


def path_length(path: JointPath) -> float:
    """Sum of the Euclidean joint-space lengths of the segments."""
    return float(segment_lengths(path).sum())


def configurations_at_arc_lengths(
    path: JointPath, arc_lengths: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """Configurations at the given distances along the path (clipped to [0, length])."""
    cumulative = np.concatenate([[0.0], np.cumsum(segment_lengths(path))])
    targets = np.clip(arc_lengths, 0.0, cumulative[-1])
    segment = np.clip(np.searchsorted(cumulative, targets, side="right") - 1, 0, len(path) - 2)
    span = cumulative[segment + 1] - cumulative[segment]
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = np.where(span > 0.0, (targets - cumulative[segment]) / span, 0.0)
    start = path[segment]
    return np.asarray(start + fraction[:, np.newaxis] * (path[segment + 1] - start))


def resample_path(path: JointPath, count: int) -> JointPath:
    """`count` configurations equally spaced by arc length, first and last kept exactly."""
    if count < 2:
        raise ValueError(f"need at least 2 waypoints to resample a path, got {count}")
    if len(path) == 1:
        return np.repeat(path, count, axis=0)
    resampled = configurations_at_arc_lengths(path, np.linspace(0.0, path_length(path), count))
    resampled[0], resampled[-1] = path[0], path[-1]
    return resampled


def densify_path(path: JointPath, resolution: float) -> JointPath:
    """Insert configurations so consecutive rows are at most `resolution` apart.

    Every original waypoint is kept.
    """
    if resolution <= 0.0:
        raise ValueError(f"resolution must be positive, got {resolution}")
    pieces = [path[:1]]
    for q0, q1 in itertools.pairwise(path):
        intervals = max(1, int(np.ceil(np.linalg.norm(q1 - q0) / resolution)))
        fractions = np.arange(1, intervals + 1)[:, np.newaxis] / intervals
        pieces.append(q0 + fractions * (q1 - q0))
    return np.concatenate(pieces)
