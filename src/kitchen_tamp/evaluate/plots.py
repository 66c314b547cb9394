"""The sweep's plots: success with 95% intervals, the CDF of solve times, and the median time per phase."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.figure import Figure

from kitchen_tamp.evaluate.success_statistics import group_figures, quantile

SUCCESS_PLOT = "success.png"
TIME_CDF_PLOT = "time_cdf.png"
PHASES_PLOT = "phase_times.png"
PLOTTED_PHASES = ("startup_s", "symbolic_s", "skills_s", "motion_s", "verification_s", "physics_s")
"""The phases that add up (roughly) to a run's time; ``refinement_s`` is skills plus motion."""
DPI = 120

Groups = Mapping[tuple[str, str], list[dict[str, str]]]


def _label(key: tuple[str, str]) -> str:
    return f"{key[0]}, {key[1]}"


def _save(figure: Figure, path: Path) -> Path:
    figure.tight_layout()
    temporary = path.with_name(f".{path.name}.tmp.png")
    figure.savefig(temporary, dpi=DPI)
    plt.close(figure)
    temporary.replace(path)
    return path


def success_plot(groups: Groups, path: Path) -> Path:
    """One bar per (problem, mode): the success rate with its 95% Wilson interval."""
    keys = list(groups)
    figures = [group_figures(groups[key]) for key in keys]
    figure, axes = plt.subplots(figsize=(7.0, 1.0 + 0.4 * max(len(keys), 1)))
    rates = [100 * f.rate for f in figures]
    below = [100 * (f.rate - f.interval[0]) for f in figures]
    above = [100 * (f.interval[1] - f.rate) for f in figures]
    axes.barh(range(len(keys)), rates, xerr=[below, above], color="tab:green", capsize=3)
    labels = [f"{_label(key)} ({f.solved}/{f.runs})" for key, f in zip(keys, figures, strict=True)]
    axes.set_yticks(range(len(keys)), labels)
    axes.invert_yaxis()
    axes.set_xlim(0, 100)
    axes.set_xlabel("solved and verified, % (95% Wilson interval)")
    return _save(figure, path)


def time_cdf_plot(groups: Groups, path: Path) -> Path:
    """Fraction of a group's tasks solved within t seconds (unsolved tasks never arrive)."""
    figure, axes = plt.subplots(figsize=(7.0, 4.0))
    for key, rows in groups.items():
        times = sorted(float(r["wall_s"]) for r in rows if r["status"] == "solved")
        if not times:
            continue
        fractions = [(i + 1) / len(rows) for i in range(len(times))]
        axes.step([0.0, *times], [0.0, *fractions], where="post", label=_label(key))
    axes.set_xscale("log")
    axes.set_xlabel("wall seconds per task (log)")
    axes.set_ylabel("fraction of tasks solved")
    axes.set_ylim(0, 1.02)
    axes.grid(alpha=0.3)
    axes.legend(fontsize="small")
    return _save(figure, path)


def phase_plot(groups: Groups, path: Path) -> Path:
    """Where the time of the solved tasks goes: the median seconds of each phase, stacked."""
    keys = list(groups)
    figure, axes = plt.subplots(figsize=(7.0, 1.0 + 0.4 * max(len(keys), 1)))
    left = [0.0] * len(keys)
    for phase in PLOTTED_PHASES:
        medians = []
        for key in keys:
            values = [float(r[phase]) for r in groups[key] if r["status"] == "solved" and r[phase]]
            medians.append(quantile(values, 0.5) or 0.0)
        if any(medians):
            axes.barh(range(len(keys)), medians, left=left, label=phase.removesuffix("_s"))
            left = [a + b for a, b in zip(left, medians, strict=True)]
    axes.set_yticks(range(len(keys)), [_label(k) for k in keys])
    axes.invert_yaxis()
    axes.set_xlabel("median seconds of the solved tasks, by phase")
    axes.legend(fontsize="small", ncols=3)
    return _save(figure, path)


def write_plots(out_dir: Path, groups: Groups) -> list[Path]:
    """``success.png``, ``time_cdf.png`` and ``phase_times.png`` in ``out_dir``."""
    return [
        success_plot(groups, out_dir / SUCCESS_PLOT),
        time_cdf_plot(groups, out_dir / TIME_CDF_PLOT),
        phase_plot(groups, out_dir / PHASES_PLOT),
    ]
