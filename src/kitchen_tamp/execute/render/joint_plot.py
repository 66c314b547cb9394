"""``joints.png``: joint angles over time with action boundaries marked.

Matplotlib is imported when a plot is drawn (its Agg canvas, without pyplot), not when
the package is: a run's start-up does not wait for it.
"""

from __future__ import annotations

import importlib
import io
from pathlib import Path

import numpy as np

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.execute.timeline import Timeline


def load_plotting() -> None:
    """Imports what `plot_joints` draws with (a second or so), e.g. in a process that has time now."""
    importlib.import_module("matplotlib.backends.backend_agg")
    importlib.import_module("matplotlib.figure")


def plot_joints(timeline: Timeline, title: str, path: Path, show_velocities: bool = False) -> Path:
    """Plot each arm joint's angle against time (and, if asked, its velocity below),
    with a dashed line and the action's name at the start of every action."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    times, qs = timeline.joint_samples()
    rows = 2 if show_velocities else 1
    figure = Figure(figsize=(11, 3.6 * rows))
    FigureCanvasAgg(figure)
    axes = figure.subplots(rows, 1, sharex=True, squeeze=False)
    angle_axis = axes[0][0]
    for joint in range(qs.shape[1] if qs.ndim == 2 else 0):
        angle_axis.plot(times, qs[:, joint], linewidth=1.2, label=f"joint {joint + 1}")
    angle_axis.set_ylabel("angle (rad)")
    angle_axis.set_title(title)
    if show_velocities and len(times) > 1:
        velocity_axis = axes[1][0]
        dt = np.maximum(np.diff(times), 1e-9)
        velocities = np.diff(qs, axis=0) / dt[:, None]
        for joint in range(qs.shape[1]):
            velocity_axis.step(times[:-1], velocities[:, joint], where="post", linewidth=1.0)
        velocity_axis.set_ylabel("velocity (rad/s)")
    for row in axes:
        for start in timeline.step_starts:
            row[0].axvline(float(start), color="0.5", linestyle="--", linewidth=0.8)
    top = angle_axis.get_ylim()[1]
    for start, action in zip(timeline.step_starts, timeline.actions, strict=True):
        angle_axis.text(
            float(start), top, " " + action, rotation=90, va="top", ha="left", fontsize=7, color="0.3"
        )
    axes[-1][0].set_xlabel("time (s) at nominal joint speed")
    if len(times):
        angle_axis.legend(loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=7)
    else:
        angle_axis.text(0.5, 0.5, "no motion: the plan has no actions", ha="center",
                        transform=angle_axis.transAxes)
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=100)
    return write_atomically(path, buffer.getvalue())
