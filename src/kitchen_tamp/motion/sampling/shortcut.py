"""Path smoothing as its own step: vertex shortcuts, random shortcuts, pruning, corner cutting.

Nearly all the time smoothing takes goes to collision checks, and a segment
that turns out free costs its whole length / `edge_resolution` checks. So:

- new waypoints are put on the grid of configurations at which the segment
  they lie on was checked, so the pieces of that segment kept in the path need
  no new check (see `_piece_known_free`);
- waypoints are first joined greedily to the furthest waypoint they see, which
  removes most of a planner's detours for a few segment checks;
- waypoints are pruned before corners are cut, not after: a cut corner leaves two
  waypoints close together whose pruning would re-check most of the neighbouring
  segments (on the kitchen's queries pruning first takes about a fifth fewer checks
  in all, for paths no longer);
- a random shortcut is only checked when it would shorten the path by at least
  `min_gain_per_length` of its own length (short gains on long segments are
  where checks used to go), and random shortcutting stops after
  `max_unsuccessful_tries` tries in a row took none. Both rules look at
  lengths and tries, not time, so a seed gives the same path on any machine.
"""

from __future__ import annotations

import bisect
import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.joint_spacing import interval_count, joint_distance
from kitchen_tamp.motion.collision_checker import CollisionChecker, JointConfiguration
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.sampling.counter_samples import checked_seed, counter_uniforms
from kitchen_tamp.motion.sampling.shortcut_settings import ShortcutHyperparameters, SmoothingResult
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker

MIN_IMPROVEMENT = 1e-9
"""A shortcut must shorten the path by more than this (radians) to be taken."""
TRIES_DRAWN_AT_ONCE = 64
"""Random tries whose two uniforms are drawn at once."""
TRIES_STREAM_START = 2**40
"""Where in its seed's counter-based stream (`counter_samples`) the tries' pairs of uniforms start:
try ``k`` takes pair ``TRIES_STREAM_START + k``, far from the samples RRT-Connect draws from the
same seed's start. Creating numpy's generator instead cost a cold shortcut 120 us (17 warm)."""


def _grid_configuration(
    q0: JointConfiguration, q1: JointConfiguration, index: int, intervals: int
) -> JointConfiguration:
    """The `index`-th of the configurations a check of q0 -> q1 in `intervals` intervals visits."""
    if index == 0:
        return q0.copy()
    if index == intervals:
        return q1.copy()
    return np.asarray(q0 + (index / intervals) * (q1 - q0), dtype=np.float64)


def _piece_known_free(
    segments: CountingSegmentChecker, q0: JointConfiguration, q1: JointConfiguration, grid_steps: int
) -> bool:
    """Whether q0 -> q1, a piece `grid_steps` grid steps long of a checked segment, is free.

    A segment of length L is checked in n = ceil(L / resolution) equal
    intervals. A piece of it between two of its grid configurations k apart
    has ceil(k L / (n resolution)) = k intervals of its own (L / resolution is
    in (n - 1, n], so k L / (n resolution) is in (k - 1, k]): checking it would
    visit the same grid configurations again (up to rounding), so it is free.
    Only when rounding makes the counts differ (L about a whole number of
    resolutions, as RRT-Connect's edges are) is the piece checked on its own points.
    """
    if grid_steps == 0 or interval_count(q0, q1, segments.resolution) == grid_steps:
        return True
    return segments.segment_valid(q0, q1, check_start=False, check_end=False)


@dataclass(frozen=True)
class _Arcs:
    """A path's segment lengths, their running sums from the start (one more, beginning at 0) and
    the intervals each segment is checked in: what every random try on the path reads, computed
    once per path rather than per try."""

    lengths: list[float]
    cumulative: list[float]
    intervals: list[int]

    @classmethod
    def of(cls, path: JointPath, resolution: float) -> _Arcs:
        lengths = [joint_distance(q0, q1) for q0, q1 in itertools.pairwise(path)]
        intervals = [interval_count(q0, q1, resolution) for q0, q1 in itertools.pairwise(path)]
        return cls(lengths, [0.0, *itertools.accumulate(lengths)], intervals)

    def grid_point(self, path: JointPath, arc_length: float) -> tuple[int, int]:
        """(segment, grid index) of the configuration at which the segment holding ``arc_length``
        was checked nearest to it."""
        segment = min(bisect.bisect_right(self.cumulative, arc_length) - 1, len(path) - 2)
        fraction = (arc_length - self.cumulative[segment]) / max(self.lengths[segment], 1e-300)
        intervals = self.intervals[segment]
        return segment, min(max(round(fraction * intervals), 0), intervals)


def _try_shortcut(
    path: JointPath,
    arcs: _Arcs,
    segments: CountingSegmentChecker,
    units: Sequence[float],
    min_gain_per_length: float,
) -> JointPath | None:
    """Join the two points along the path at ``units`` (uniforms in [0, 1)) of its length (snapped
    to the checked grid) by a straight segment if that gains enough length and is free."""
    low_arc, high_arc = sorted(unit * arcs.cumulative[-1] for unit in units)
    first, low_index = arcs.grid_point(path, low_arc)
    last, high_index = arcs.grid_point(path, high_arc)
    if first >= last:
        return None
    low_intervals, high_intervals = arcs.intervals[first], arcs.intervals[last]
    replaced = (
        arcs.lengths[first] * (1.0 - low_index / low_intervals)
        + sum(arcs.lengths[first + 1 : last])
        + arcs.lengths[last] * (high_index / high_intervals)
    )
    q_low = _grid_configuration(path[first], path[first + 1], low_index, low_intervals)
    q_high = _grid_configuration(path[last], path[last + 1], high_index, high_intervals)
    direct = joint_distance(q_low, q_high)
    gain = replaced - direct
    if gain <= MIN_IMPROVEMENT or gain < min_gain_per_length * direct:
        return None
    if not (
        segments.segment_valid(q_low, q_high, check_start=False, check_end=False)
        and _piece_known_free(segments, path[first], q_low, low_index)
        and _piece_known_free(segments, q_high, path[last + 1], high_intervals - high_index)
    ):
        return None
    return np.concatenate([path[: first + 1], [q_low, q_high], path[last + 1 :]])


def _without_repeats(path: JointPath) -> JointPath:
    """Drop waypoints equal to their predecessor."""
    keep = np.concatenate([[True], np.any(np.diff(path, axis=0) != 0.0, axis=1)])
    return np.asarray(path[keep], dtype=np.float64)


def _furthest_vertex_jumps(path: JointPath, segments: CountingSegmentChecker) -> list[int]:
    """Indices of the waypoints `connect_furthest_vertices` keeps."""
    kept = [0]
    while kept[-1] < len(path) - 1:
        here = kept[-1]
        reachable = next(
            (
                there
                for there in range(len(path) - 1, here + 1, -1)
                if segments.segment_valid(path[here], path[there], check_start=False, check_end=False)
            ),
            here + 1,
        )
        kept.append(reachable)
    return kept


def connect_furthest_vertices(path: JointPath, segments: CountingSegmentChecker) -> JointPath:
    """One greedy pass: from the start, go straight to the furthest waypoint in free sight, repeat.

    Candidates are tried furthest first; each segment check fails fast on a
    blocked line (coarse to fine). Waypoints are assumed valid, as on a checked
    path. Straight lines replace sub-paths, so the path never grows longer.
    """
    return np.asarray(path[_furthest_vertex_jumps(path, segments)], dtype=np.float64)


CORNER_CUT_FRACTIONS = (0.5, 0.25, 0.125)
"""Where `cut_corners` tries to start and end a cut, as fractions of the adjacent segments."""


def cut_corners(path: JointPath, segments: CountingSegmentChecker) -> JointPath:
    """One pass replacing each interior waypoint by a free cut across its corner.

    For waypoint v between neighbours a and b, tries the segment from near
    v + t (a - v) to near v + t (b - v) for t in `CORNER_CUT_FRACTIONS`,
    largest first, each end snapped to the nearest configuration at which its
    segment was checked; so the pieces a -> cut and cut -> b left of those
    segments need no new check (see `_piece_known_free`), only the cut does.
    The cut is no longer than the corner it replaces (triangle inequality), so
    the path never grows longer. Repeated passes round corners off.
    """
    resolution = segments.resolution
    kept = [path[0]]
    for index in range(1, len(path) - 1):
        before, corner, after = kept[-1], path[index], path[index + 1]
        incoming = interval_count(before, corner, resolution)
        outgoing = interval_count(corner, after, resolution)
        for fraction in CORNER_CUT_FRACTIONS:
            back, forward = round(fraction * incoming), round(fraction * outgoing)
            if back == 0 or forward == 0:
                continue
            cut_start = _grid_configuration(before, corner, incoming - back, incoming)
            cut_end = _grid_configuration(corner, after, forward, outgoing)
            if (
                segments.segment_valid(cut_start, cut_end, check_start=False, check_end=False)
                and _piece_known_free(segments, before, cut_start, incoming - back)
                and _piece_known_free(segments, cut_end, after, outgoing - forward)
            ):
                kept.extend([cut_start, cut_end])
                break
        else:
            kept.append(corner)
    kept.append(path[-1])
    return np.stack(kept)


def prune_waypoints(path: JointPath, segments: CountingSegmentChecker) -> JointPath:
    """One pass: drop each interior waypoint whose neighbours see each other freely.

    Waypoints are assumed valid, as on a checked path.
    """
    kept = [path[0]]
    for index in range(1, len(path) - 1):
        if not segments.segment_valid(kept[-1], path[index + 1], check_start=False, check_end=False):
            kept.append(path[index])
    kept.append(path[-1])
    return np.stack(kept)


def _length(path: JointPath) -> float:
    """The path's length, its segments' `joint_distance`s summed in order."""
    return sum((joint_distance(q0, q1) for q0, q1 in itertools.pairwise(path)), 0.0)


class _PythonSteps:
    """The shortcut's steps through a `CountingSegmentChecker` of any checker (a
    `compiled_shortcut.CompiledShortcutSteps` takes them for the sphere model): each counts its
    checks, and the random tries their tries, shortcuts and tries in a row that took none."""

    def __init__(self, checker: CollisionChecker, resolution: float) -> None:
        self.segments = CountingSegmentChecker(checker, resolution)
        self.tries = self.shortcuts = self.unsuccessful = 0

    @property
    def checks(self) -> int:
        return self.segments.configurations_checked

    def connect_furthest(self, path: JointPath) -> JointPath:
        kept = _furthest_vertex_jumps(path, self.segments)
        self.shortcuts += int(np.count_nonzero(np.diff(kept) > 1))
        return np.asarray(path[kept], dtype=np.float64)

    def random_tries(
        self,
        path: JointPath,
        units: npt.NDArray[np.float64],
        params: ShortcutHyperparameters,
        deadline: float,
    ) -> JointPath:
        """A try per row of ``units`` until they run out or a limit is hit (the clock read per try)."""
        arcs = _Arcs.of(path, self.segments.resolution)
        for unit_pair in units.tolist():
            if _tries_over(self.tries, self.unsuccessful, len(path), params) or params.clock() >= deadline:
                break
            shorter = _try_shortcut(path, arcs, self.segments, unit_pair, params.min_gain_per_length)
            self.tries += 1
            if shorter is None:
                self.unsuccessful += 1
            else:
                path = _without_repeats(shorter)
                arcs = _Arcs.of(path, self.segments.resolution)
                self.shortcuts += 1
                self.unsuccessful = 0
        return path

    def prune(self, path: JointPath) -> JointPath:
        return prune_waypoints(path, self.segments)

    def cut_corners(self, path: JointPath) -> JointPath:
        return _without_repeats(cut_corners(path, self.segments))


def _tries_over(tries: int, unsuccessful: int, waypoints: int, params: ShortcutHyperparameters) -> bool:
    """Whether random shortcutting stops: the tries used up, the patience spent, or one segment left."""
    patience = params.max_unsuccessful_tries
    patient = patience is None or unsuccessful < patience
    return tries >= params.max_iterations or waypoints <= 2 or not patient


def shortcut_path(
    path: JointPath,
    checker: CollisionChecker,
    hyperparameters: ShortcutHyperparameters | None = None,
    *,
    seed: int = 0,
    time_budget_s: float = 1.0,
) -> SmoothingResult:
    """Shorten a collision-free path: vertex shortcuts, random shortcuts, pruning, corner cutting.

    Random shortcut endpoints are drawn uniformly by arc length, then moved to
    the nearest configuration at which their segment was checked; a shortcut
    is taken when it is strictly shorter (by at least `min_gain_per_length` of
    its length) and its straight segment is free at `edge_resolution`. So
    every segment of the result has been checked on exactly the points
    `check_path_densely(result, checker, edge_resolution)` visits (up to
    floating-point rounding of the interpolation; given the same holds for
    `path`, as it does for our planners). Endpoints are kept exactly; the
    result is never longer. The result depends only on the path, the checker,
    the hyperparameters and `seed`, unless `time_budget_s` runs out first.
    With the sphere model as the checker (a `CompiledValidity` that answers), the steps run
    compiled (`compiled_shortcut`): the same path and counts, the clock read between blocks of
    tries instead of before each.
    """
    params = hyperparameters or ShortcutHyperparameters()
    clock = params.clock
    clock_start = clock()
    deadline = clock_start + time_budget_s
    seed = checked_seed(seed)
    steps = _steps_for(checker, params.edge_resolution)
    current = _without_repeats(np.array(path, dtype=np.float64))
    if params.connect_furthest_vertices and len(current) > 2:
        current = steps.connect_furthest(current)
    while not _tries_over(steps.tries, steps.unsuccessful, len(current), params) and clock() < deadline:
        first = TRIES_STREAM_START + steps.tries
        units = counter_uniforms(seed, first, TRIES_DRAWN_AT_ONCE, np.zeros(2), np.ones(2))  # in [0, 1)
        current = steps.random_tries(current, units, params, deadline)
    if params.prune_waypoints and len(current) > 2:
        pruned = steps.prune(current)
        if _length(pruned) <= _length(current):
            current = pruned
    for _ in range(params.corner_cutting_passes):
        if len(current) <= 2 or clock() >= deadline:
            break
        current = steps.cut_corners(current)
    return SmoothingResult(
        path=current,
        iterations=steps.tries,
        shortcuts_taken=steps.shortcuts,
        collision_checks=steps.checks,
        smoothing_time_s=clock() - clock_start,
    )


def _steps_for(checker: CollisionChecker, resolution: float) -> Any:
    """The compiled steps when the checker offers its compiled validity, else the Python ones."""
    offered = getattr(checker, "compiled_validity", None)  # `CompiledValidity`, without isinstance
    compiled = offered() if callable(offered) else None
    if compiled is None:
        return _PythonSteps(checker, resolution)
    from kitchen_tamp.motion.sampling.compiled_shortcut import CompiledShortcutSteps

    return CompiledShortcutSteps(compiled, resolution)
