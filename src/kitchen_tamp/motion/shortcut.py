"""Path smoothing as its own step: random shortcuts, corner cutting, waypoint pruning."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.motion.collision_checker import CollisionChecker
from kitchen_tamp.motion.joint_path import (
    JointPath,
    configurations_at_arc_lengths,
    path_length,
    segment_lengths,
)
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker

MIN_IMPROVEMENT = 1e-9
"""A shortcut must shorten the path by more than this (radians) to be taken."""


@dataclass(frozen=True)
class ShortcutHyperparameters:
    """Budgets and segment-check resolution of `shortcut_path`.

    `max_iterations` random shortcuts are tried, then `corner_cutting_passes`
    passes of `cut_corners`, then (if `prune_waypoints`) one pruning pass.
    """

    max_iterations: int = 200
    edge_resolution: float = 0.01
    corner_cutting_passes: int = 3
    prune_waypoints: bool = True

    def __post_init__(self) -> None:
        if self.max_iterations < 0:
            raise ValueError(f"max_iterations must be non-negative, got {self.max_iterations}")
        if self.corner_cutting_passes < 0:
            raise ValueError(f"corner_cutting_passes must be non-negative, got {self.corner_cutting_passes}")
        if self.edge_resolution <= 0.0:
            raise ValueError(f"edge_resolution must be positive, got {self.edge_resolution}")


@dataclass(frozen=True, eq=False)
class SmoothingResult:
    """A smoothed path (same endpoints, never longer) and what smoothing it cost."""

    path: JointPath
    iterations: int
    shortcuts_taken: int
    collision_checks: int
    smoothing_time_s: float


def _try_shortcut(
    path: JointPath, segments: CountingSegmentChecker, rng: np.random.Generator
) -> JointPath | None:
    """Join two random points along the path by a straight segment if that is free and shorter."""
    lengths = segment_lengths(path)
    cumulative = np.concatenate([[0.0], np.cumsum(lengths)])
    low, high = np.sort(rng.uniform(0.0, cumulative[-1], size=2))
    first = int(np.searchsorted(cumulative, low, side="right")) - 1
    last = int(np.searchsorted(cumulative, high, side="right")) - 1
    if first >= last:
        return None
    q_low, q_high = configurations_at_arc_lengths(path, np.array([low, high]))
    if high - low - np.linalg.norm(q_high - q_low) <= MIN_IMPROVEMENT:
        return None
    if not segments.segment_valid(q_low, q_high):
        return None
    if not (
        segments.segment_valid(path[first], q_low, check_start=False, check_end=False)
        and segments.segment_valid(q_high, path[last + 1], check_start=False, check_end=False)
    ):
        return None
    return np.concatenate([path[: first + 1], [q_low, q_high], path[last + 1 :]])


def _without_repeats(path: JointPath) -> JointPath:
    """Drop waypoints equal to their predecessor."""
    keep = np.concatenate([[True], np.any(np.diff(path, axis=0) != 0.0, axis=1)])
    return np.asarray(path[keep], dtype=np.float64)


CORNER_CUT_FRACTIONS = (0.5, 0.25, 0.125)
"""Where `cut_corners` tries to start and end a cut, as fractions of the adjacent segments."""


def cut_corners(path: JointPath, segments: CountingSegmentChecker) -> JointPath:
    """One pass replacing each interior waypoint by a free cut across its corner.

    For waypoint v between neighbours a and b, tries the segment from
    v + t (a - v) to v + t (b - v) for t in `CORNER_CUT_FRACTIONS`, largest
    first; the cut and the two pieces left of a -> v and v -> b are each
    checked on their own points. The cut is no longer than the corner it
    replaces (triangle inequality), so the path never grows longer.
    Repeated passes round corners off.
    """
    kept = [path[0]]
    for index in range(1, len(path) - 1):
        before, corner, after = kept[-1], path[index], path[index + 1]
        for fraction in CORNER_CUT_FRACTIONS:
            cut_start = corner + fraction * (before - corner)
            cut_end = corner + fraction * (after - corner)
            if (
                segments.segment_valid(cut_start, cut_end)
                and segments.segment_valid(before, cut_start, check_start=False, check_end=False)
                and segments.segment_valid(cut_end, after, check_start=False, check_end=False)
            ):
                kept.extend([cut_start, cut_end])
                break
        else:
            kept.append(corner)
    kept.append(path[-1])
    return np.stack(kept)


def prune_waypoints(path: JointPath, segments: CountingSegmentChecker) -> JointPath:
    """One pass: drop each interior waypoint whose neighbours see each other freely."""
    kept = [path[0]]
    for index in range(1, len(path) - 1):
        if not segments.segment_valid(kept[-1], path[index + 1], check_start=False):
            kept.append(path[index])
    kept.append(path[-1])
    return np.stack(kept)


def shortcut_path(
    path: JointPath,
    checker: CollisionChecker,
    hyperparameters: ShortcutHyperparameters | None = None,
    *,
    seed: int = 0,
    time_budget_s: float = 1.0,
) -> SmoothingResult:
    """Shorten a collision-free path: random shortcuts, corner cutting, then pruning.

    Shortcut endpoints are drawn uniformly by arc length, so they may fall
    inside segments; a shortcut is taken when it is strictly shorter and its
    straight segment, and the two pieces left of the segments it cuts into,
    are free at `edge_resolution`. So every segment of the result has been
    checked on exactly the points `check_path_densely(result, checker,
    edge_resolution)` visits (given the same holds for `path`, as it does for
    our planners). Endpoints are kept exactly; the result is never longer.
    """
    params = hyperparameters or ShortcutHyperparameters()
    clock_start = time.perf_counter()
    deadline = clock_start + time_budget_s
    rng = np.random.default_rng(seed)
    segments = CountingSegmentChecker(checker, params.edge_resolution)
    current = _without_repeats(np.array(path, dtype=np.float64))
    shortcuts = 0
    iterations = 0
    while iterations < params.max_iterations and len(current) > 2:
        if time.perf_counter() >= deadline:
            break
        iterations += 1
        shorter = _try_shortcut(current, segments, rng)
        if shorter is not None:
            current = _without_repeats(shorter)
            shortcuts += 1
    for _ in range(params.corner_cutting_passes):
        if len(current) <= 2 or time.perf_counter() >= deadline:
            break
        current = _without_repeats(cut_corners(current, segments))
    if params.prune_waypoints and len(current) > 2:
        pruned = prune_waypoints(current, segments)
        if path_length(pruned) <= path_length(current):
            current = pruned
    return SmoothingResult(
        path=current,
        iterations=iterations,
        shortcuts_taken=shortcuts,
        collision_checks=segments.configurations_checked,
        smoothing_time_s=time.perf_counter() - clock_start,
    )
