"""Summary figures: the Wilson interval, quantiles and failure causes of a group of rows."""

from __future__ import annotations

import pytest

from kitchen_tamp.evaluate.success_statistics import group_figures, quantile, wilson_interval


@pytest.mark.parametrize(
    ("successes", "trials", "low", "high"),
    [(8, 10, 0.4902, 0.9433), (0, 10, 0.0, 0.2775), (10, 10, 0.7225, 1.0), (1, 2, 0.0945, 0.9055)],
)
def test_wilson_interval_matches_published_values(
    successes: int, trials: int, low: float, high: float
) -> None:
    assert wilson_interval(successes, trials) == pytest.approx((low, high), abs=1e-4)


def test_the_interval_always_holds_the_observed_rate() -> None:
    # at 0% and 100% rounding once put an end a hair inside the rate: a negative error bar
    # crashed the success plot of a 10-seed sweep
    for trials in range(1, 101):
        for successes in range(trials + 1):
            low, high = wilson_interval(successes, trials)
            assert 0.0 <= low <= successes / trials <= high <= 1.0


def test_no_trials_tells_nothing() -> None:
    assert wilson_interval(0, 0) == (0.0, 1.0)


def test_quantiles_interpolate() -> None:
    assert quantile([], 0.5) is None
    assert quantile([3.0], 0.9) == 3.0
    assert quantile([4.0, 1.0, 3.0, 2.0], 0.5) == 2.5
    assert quantile([float(v) for v in range(11)], 0.9) == pytest.approx(9.0)


def _row(status: str, stage: str = "", wall: str = "", path: str = "", physics: str = "") -> dict[str, str]:
    return {"status": status, "failure_stage": stage, "wall_s": wall, "path_length_rad": path,
            "samples": "5" if status == "solved" else "", "physics_verified": physics}


def test_group_figures_count_successes_times_and_causes() -> None:
    rows = [
        _row("solved", wall="2.0", path="10.0", physics="true"),
        _row("solved", wall="4.0", path="12.0", physics="false"),
        _row("failed", "refinement", wall="9.0"),
        _row("timeout", "timeout", wall="60.0"),
        _row("failed", "refinement", wall="7.0"),
    ]
    figures = group_figures(rows)
    assert (figures.runs, figures.solved) == (5, 2)
    assert figures.rate == pytest.approx(0.4)
    assert figures.median_time_s == pytest.approx(3.0)  # solved tasks only
    assert figures.median_path_rad == pytest.approx(11.0)
    assert figures.causes == {"refinement": 2, "timeout": 1}
    assert (figures.physics_checked, figures.physics_verified) == (2, 1)
