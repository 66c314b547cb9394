"""What `shortcut.shortcut_path` is given (`ShortcutHyperparameters`) and what it returns
(`SmoothingResult`)."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from kitchen_tamp.joint_spacing import PLANNING_RESOLUTION_RAD
from kitchen_tamp.motion.joint_path import JointPath


@dataclass(frozen=True)
class ShortcutHyperparameters:
    """Budgets and segment-check resolution of `shortcut_path`.

    If `connect_furthest_vertices`, waypoints are first joined greedily to the
    furthest waypoint they see. Then up to `max_iterations` random shortcuts
    are tried, stopping early after `max_unsuccessful_tries` tries in a row
    took none (None: never stop early); a try whose shortcut would save less
    than `min_gain_per_length` times its own length counts as unsuccessful
    without a collision check. Then (if `prune_waypoints`) one pruning pass,
    then `corner_cutting_passes` passes of `cut_corners`.

    The defaults were chosen on the kitchen queries of `benchmarks/motion.py`:
    about a twelfth of the checks of the former ones (200 tries, each checked,
    3 corner passes), for median paths at most 2% longer, about 20% shorter
    than OMPL's simplified ones.
    """

    max_iterations: int = 200
    edge_resolution: float = PLANNING_RESOLUTION_RAD
    corner_cutting_passes: int = 1
    prune_waypoints: bool = True
    connect_furthest_vertices: bool = True
    max_unsuccessful_tries: int | None = 20
    min_gain_per_length: float = 0.03
    clock: Callable[[], float] = time.perf_counter
    """What the time budget is measured on: wall seconds; ``time.process_time`` for CPU seconds."""

    def __post_init__(self) -> None:
        if self.max_iterations < 0:
            raise ValueError(f"max_iterations must be non-negative, got {self.max_iterations}")
        if self.corner_cutting_passes < 0:
            raise ValueError(f"corner_cutting_passes must be non-negative, got {self.corner_cutting_passes}")
        if self.edge_resolution <= 0.0:
            raise ValueError(f"edge_resolution must be positive, got {self.edge_resolution}")
        if self.max_unsuccessful_tries is not None and self.max_unsuccessful_tries < 1:
            raise ValueError(
                f"max_unsuccessful_tries must be at least 1 (or None), got {self.max_unsuccessful_tries}"
            )
        if self.min_gain_per_length < 0.0:
            raise ValueError(f"min_gain_per_length must be non-negative, got {self.min_gain_per_length}")


@dataclass(frozen=True, eq=False)
class SmoothingResult:
    """A smoothed path (same endpoints, never longer) and what smoothing it cost.

    `iterations` counts random shortcut tries; `shortcuts_taken` counts every
    shortcut taken, between waypoints or random.
    """

    path: JointPath
    iterations: int
    shortcuts_taken: int
    collision_checks: int
    smoothing_time_s: float
