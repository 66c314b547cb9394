"""Figures of a group of results rows: success with a Wilson interval, time and path quantiles, causes."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

Z_95 = 1.959963984540054
"""The standard normal quantile of a two-sided 95% interval."""


def wilson_interval(successes: int, trials: int, z: float = Z_95) -> tuple[float, float]:
    """The Wilson score interval of a success rate (0..1); (0, 1) when there are no trials."""
    if trials == 0:
        return 0.0, 1.0
    rate = successes / trials
    denominator = 1.0 + z * z / trials
    centre = (rate + z * z / (2 * trials)) / denominator
    half = z * math.sqrt(rate * (1 - rate) / trials + z * z / (4 * trials * trials)) / denominator
    # the interval holds the observed rate; rounding can put an end a hair past it (at 0% or 100%)
    return max(0.0, min(rate, centre - half)), min(1.0, max(rate, centre + half))


def quantile(values: Sequence[float], q: float) -> float | None:
    """The ``q`` quantile with linear interpolation, None for no values."""
    if not values:
        return None
    ordered = sorted(values)
    position = q * (len(ordered) - 1)
    low = math.floor(position)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (position - low)


def _numbers(rows: Iterable[dict[str, str]], column: str) -> list[float]:
    return [float(row[column]) for row in rows if row.get(column)]


@dataclass(frozen=True)
class GroupFigures:
    """The summary figures of one (problem, mode) group."""

    runs: int
    solved: int
    interval: tuple[float, float]
    median_time_s: float | None
    p90_time_s: float | None
    median_path_rad: float | None
    median_samples: float | None
    median_plans: float | None
    """Abstract plans tried, over every run that planned (solved or not)."""
    median_facts: float | None
    """Facts learned from failures, over every run that planned."""
    causes: Counter[str]
    physics_checked: int
    physics_verified: int

    @property
    def rate(self) -> float:
        return self.solved / self.runs if self.runs else 0.0


def failure_cause(row: dict[str, str]) -> str:
    """``timeout``, ``crashed``, ``bad_input`` or the stage at which a run failed."""
    return row["failure_stage"] or row["status"]


def group_figures(rows: Sequence[dict[str, str]]) -> GroupFigures:
    """Success over all rows; times, path lengths and samples over the solved ones (wall seconds)."""
    solved = [row for row in rows if row["status"] == "solved"]
    times = _numbers(solved, "wall_s")
    physics = [row["physics_verified"] for row in rows if row["physics_verified"]]
    samples = _numbers(solved, "samples")
    return GroupFigures(
        runs=len(rows),
        solved=len(solved),
        interval=wilson_interval(len(solved), len(rows)),
        median_time_s=quantile(times, 0.5),
        p90_time_s=quantile(times, 0.9),
        median_path_rad=quantile(_numbers(solved, "path_length_rad"), 0.5),
        median_samples=quantile(samples, 0.5),
        median_plans=quantile(_numbers(rows, "abstract_plans_tried"), 0.5),
        median_facts=quantile(_numbers(rows, "facts_learned"), 0.5),
        causes=Counter(failure_cause(row) for row in rows if row["status"] != "solved"),
        physics_checked=len(physics),
        physics_verified=sum(value == "true" for value in physics),
    )
