"""``joints.png``: joint angles over time with action boundaries marked.

Every run draws it, so it is drawn with Pillow (the GIF's library, a few hundredths of a second
to import) and not matplotlib, whose import took 0.4-0.8 s of every run here (the evaluation's
sweep plots, made once per sweep, keep matplotlib). The picture: one coloured line per joint
against time on axes with ticks at round values and a legend, a dashed line and the action's
name at the start of every action, and with ``optimizes`` the joints' velocities below, held
from waypoint to waypoint.
"""

from __future__ import annotations

import importlib
import io
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.execute.timeline import Timeline
from kitchen_tamp.world import FloatArray

WIDTH = 1100
PANEL_HEIGHT = 330
"""Pixels of the picture's width and of each panel (angles; velocities below them)."""
MARGINS = (72, 40, 120, 48)
"""Left (tick labels), top (title), right (legend) and bottom (time axis) margins, in pixels."""
JOINT_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
                 "#7f7f7f", "#bcbd22", "#17becf")
"""Line colours, joint by joint (matplotlib's ten-colour cycle, which the plot used before)."""
AXIS_COLOUR, BOUNDARY_COLOUR, LABEL_COLOUR = "#000000", "#808080", "#4d4d4d"
FONT_SIZE, SMALL_FONT_SIZE = 13, 10


def load_plotting() -> None:
    """Imports what `plot_joints` draws with, e.g. in a process that has time now."""
    importlib.import_module("PIL.ImageDraw")
    importlib.import_module("PIL.ImageFont")


def round_ticks(low: float, high: float, most: int = 7) -> list[float]:
    """Ticks at multiples of 1, 2 or 5 times a power of ten, at most ``most`` of them, within
    [low, high] (which must be increasing)."""
    span = high - low
    for step in (m * 10.0 ** e for e in range(math.floor(math.log10(span / most)), 20) for m in (1, 2, 5)):
        if span / step <= most - 1:
            first = math.ceil(low / step - 1e-9)
            count = math.floor(high / step + 1e-9) - first + 1
            return [round((first + k) * step, 12) for k in range(count)]
    return [low, high]


def _tick_text(value: float) -> str:
    return f"{value:g}" if abs(value) >= 1e-12 else "0"


@dataclass(frozen=True)
class Panel:
    """One panel's plotting area (pixels: left, top, right, bottom) and the data ranges it shows."""

    box: tuple[int, int, int, int]
    x_range: tuple[float, float]
    y_range: tuple[float, float]

    def x(self, values: FloatArray) -> FloatArray:
        left, _, right, _ = self.box
        low, high = self.x_range
        return np.asarray(left + (np.asarray(values) - low) / (high - low) * (right - left))

    def y(self, values: FloatArray) -> FloatArray:
        _, top, _, bottom = self.box
        low, high = self.y_range
        return np.asarray(bottom - (np.asarray(values) - low) / (high - low) * (bottom - top))


def _padded(low: float, high: float) -> tuple[float, float]:
    """A data range with 5% to spare either side (one unit around a constant)."""
    if not (math.isfinite(low) and math.isfinite(high)) or high - low < 1e-9:
        middle = 0.0 if not math.isfinite(low) else low
        return middle - 1.0, middle + 1.0
    pad = 0.05 * (high - low)
    return low - pad, high + pad


Font = ImageFont.FreeTypeFont | ImageFont.ImageFont


def _font(size: int) -> Font:
    return ImageFont.load_default(size=size)


def _dashed_vertical(draw: ImageDraw.ImageDraw, x: float, top: int, bottom: int) -> None:
    for start in range(top, bottom, 8):
        draw.line([(x, start), (x, min(start + 4, bottom))], fill=BOUNDARY_COLOUR, width=1)


def _upwards(text: str, font: Font, colour: str) -> Image.Image:
    """``text`` written upwards on a transparent picture of its size."""
    left, upper, right, lower = font.getbbox(text)
    label = Image.new("RGBA", (int(right - left) + 2, int(lower - upper) + 2), (255, 255, 255, 0))
    ImageDraw.Draw(label).text((1 - left, 1 - upper), text, font=font, fill=colour)
    return label.rotate(90, expand=True)


def _axes(picture: Image.Image, panel: Panel, font: Font, y_label: str, x_ticks: bool) -> None:
    draw = ImageDraw.Draw(picture)
    left, top, _, bottom = panel.box
    draw.rectangle(panel.box, outline=AXIS_COLOUR, width=1)
    for value in round_ticks(*panel.y_range, most=9):
        y = float(panel.y(np.array(value)))
        draw.line([(left - 5, y), (left, y)], fill=AXIS_COLOUR)
        draw.text((left - 8, y), _tick_text(value), font=font, fill=AXIS_COLOUR, anchor="rm")
    for value in round_ticks(*panel.x_range, most=12):
        x = float(panel.x(np.array(value)))
        draw.line([(x, bottom), (x, bottom + 5)], fill=AXIS_COLOUR)
        if x_ticks:
            draw.text((x, bottom + 8), _tick_text(value), font=font, fill=AXIS_COLOUR, anchor="mt")
    label = _upwards(y_label, font, AXIS_COLOUR)
    picture.paste(label, (8, int((top + bottom - label.height) / 2)), label)


def _lines(
    draw: ImageDraw.ImageDraw, panel: Panel, times: FloatArray, values: FloatArray, held: bool
) -> None:
    """One line per column of ``values``; ``held``: each value held until the next time (steps,
    drawn thinner)."""
    for joint in range(values.shape[1]):
        if held:
            xs = np.repeat(panel.x(times), 2)[1:]
            ys = np.repeat(panel.y(values[:, joint]), 2)[:-1]
        else:
            xs, ys = panel.x(times), panel.y(values[:, joint])
        colour = JOINT_COLOURS[joint % len(JOINT_COLOURS)]
        draw.line(list(zip(xs.tolist(), ys.tolist(), strict=True)), fill=colour, width=1 if held else 2,
                  joint="curve")


def _legend(draw: ImageDraw.ImageDraw, panel: Panel, joints: int, font: Font) -> None:
    _, top, right, bottom = panel.box
    first = (top + bottom) / 2 - joints * 9
    for joint in range(joints):
        y = first + joint * 18
        draw.line([(right + 12, y), (right + 36, y)], fill=JOINT_COLOURS[joint % len(JOINT_COLOURS)], width=2)
        draw.text((right + 42, y), f"joint {joint + 1}", font=font, fill=AXIS_COLOUR, anchor="lm")


def draw_joint_picture(
    times: FloatArray, qs: FloatArray, title: str, step_starts: Sequence[float], actions: Sequence[str],
    show_velocities: bool = False,
) -> Image.Image:
    """The picture of joint angles ``qs`` (n, joints) at ``times`` (n), actions starting at
    ``step_starts``, with velocities below if asked."""
    rows = 2 if show_velocities else 1
    left_margin, top_margin, right_margin, bottom_margin = MARGINS
    height = top_margin + rows * PANEL_HEIGHT + (rows - 1) * 16 + bottom_margin
    picture = Image.new("RGB", (WIDTH, height), "white")
    draw = ImageDraw.Draw(picture)
    font, small = _font(FONT_SIZE), _font(SMALL_FONT_SIZE)
    draw.text((WIDTH / 2, top_margin / 2), title, font=_font(FONT_SIZE + 1), fill=AXIS_COLOUR, anchor="mm")
    moving = len(times) > 0 and qs.ndim == 2 and qs.shape[1] > 0
    duration = float(times[-1]) if moving and float(times[-1]) > float(times[0]) else 1.0
    x_range = (float(times[0]) if moving else 0.0, float(times[0]) + duration if moving else 1.0)

    def panel(row: int, values: FloatArray) -> Panel:
        top = top_margin + row * (PANEL_HEIGHT + 16)
        finite = values[np.isfinite(values)] if values.size else values
        y_range = _padded(float(finite.min()), float(finite.max())) if finite.size else (-1.0, 1.0)
        return Panel((left_margin, top, WIDTH - right_margin, top + PANEL_HEIGHT), x_range, y_range)

    angles = panel(0, qs if moving else np.zeros(0))
    panels = [angles]
    if show_velocities and moving and len(times) > 1:
        velocities = np.diff(qs, axis=0) / np.maximum(np.diff(times), 1e-9)[:, None]
        speeds = panel(1, velocities)
        panels.append(speeds)
    for index, shown in enumerate(panels):
        y_label = "angle (rad)" if index == 0 else "velocity (rad/s)"
        _axes(picture, shown, font, y_label, x_ticks=index == len(panels) - 1)
        for start in step_starts:
            _dashed_vertical(draw, float(shown.x(np.array(float(start)))), shown.box[1], shown.box[3])
    if moving:
        _lines(draw, angles, times, qs, held=False)
        _legend(draw, angles, qs.shape[1], font)
        if len(panels) > 1:
            _lines(draw, panels[1], times[:-1], velocities, held=True)
        for start, action in zip(step_starts, actions, strict=True):  # upwards from the top, beside the line
            label = _upwards(action, small, LABEL_COLOUR)
            picture.paste(label, (int(angles.x(np.array(float(start)))) + 2, angles.box[1] + 2), label)
    else:
        box = angles.box
        draw.text(((box[0] + box[2]) / 2, (box[1] + box[3]) / 2), "no motion: the plan has no actions",
                  font=font, fill=AXIS_COLOUR, anchor="mm")
    last = panels[-1].box
    draw.text(((last[0] + last[2]) / 2, last[3] + 30), "time (s) at nominal joint speed", font=font,
              fill=AXIS_COLOUR, anchor="mt")
    return picture


def plot_joints(timeline: Timeline, title: str, path: Path, show_velocities: bool = False) -> Path:
    """Plot each arm joint's angle against time (and, if asked, its velocity below),
    with a dashed line and the action's name at the start of every action."""
    times, qs = timeline.joint_samples()
    picture = draw_joint_picture(times, qs, title, [float(s) for s in timeline.step_starts],
                                 list(timeline.actions), show_velocities)
    buffer = io.BytesIO()
    picture.save(buffer, format="PNG", optimize=False)
    return write_atomically(path, buffer.getvalue())
