"""joints.png: ticks at round values, each joint's line where its values put it, the velocities'
panel when asked, and a picture for a plan without motion."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageColor

from kitchen_tamp.execute.render.joint_plot import (
    JOINT_COLOURS,
    MARGINS,
    PANEL_HEIGHT,
    WIDTH,
    Panel,
    draw_joint_picture,
    round_ticks,
)


def test_ticks_are_round_and_within_the_range() -> None:
    assert round_ticks(-2.9, 3.3, most=9) == [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0]
    assert round_ticks(0.0, 15.6, most=12) == [float(t) for t in range(0, 16, 2)]
    assert round_ticks(-0.031, 0.047) == [-0.02, 0.0, 0.02, 0.04]
    for low, high in ((0.1, 0.13), (-700.0, 12.0), (3.0, 3.5)):
        ticks = round_ticks(low, high)
        assert 2 <= len(ticks) <= 7 and all(low <= t <= high for t in ticks)


def _colour_near(picture: Image.Image, x: float, y: float, colour: str) -> bool:
    """Whether ``colour`` is within two pixels of (x, y)."""
    pixels = np.asarray(picture)[int(y) - 2 : int(y) + 3, int(x) - 2 : int(x) + 3].reshape(-1, 3)
    return bool(np.any(np.all(pixels == ImageColor.getrgb(colour), axis=1)))


def test_each_joint_is_drawn_where_its_values_are() -> None:
    times = np.linspace(0.0, 10.0, 101)
    qs = np.stack([np.full_like(times, 1.0), np.linspace(-1.0, 1.0, 101)], axis=1)
    picture = draw_joint_picture(times, qs, "two joints", [0.0, 5.0], ["(first)", "(second)"])
    assert picture.size == (WIDTH, MARGINS[1] + PANEL_HEIGHT + MARGINS[3])
    left, top, right, bottom = MARGINS[0], MARGINS[1], WIDTH - MARGINS[2], MARGINS[1] + PANEL_HEIGHT
    pad = 0.05 * 2.0
    panel = Panel((left, top, right, bottom), (0.0, 10.0), (-1.0 - pad, 1.0 + pad))
    for t in (2.5, 7.5):
        x = float(panel.x(np.array(t)))
        assert _colour_near(picture, x, float(panel.y(np.array(1.0))), JOINT_COLOURS[0])
        assert _colour_near(picture, x, float(panel.y(np.array((t - 5.0) / 5.0))), JOINT_COLOURS[1])
        assert not _colour_near(picture, x, float(panel.y(np.array(-0.9))), JOINT_COLOURS[0])


def test_velocities_are_a_second_panel(tmp_path: Path) -> None:
    times = np.linspace(0.0, 4.0, 9)
    qs = np.stack([times, -times], axis=1)  # 1 rad/s and -1 rad/s throughout
    angles_only = draw_joint_picture(times, qs, "angles", [0.0], ["(go)"])
    both = draw_joint_picture(times, qs, "angles and velocities", [0.0], ["(go)"], show_velocities=True)
    assert both.size[1] > angles_only.size[1] + PANEL_HEIGHT
    top = MARGINS[1] + PANEL_HEIGHT + 16
    panel = Panel((MARGINS[0], top, WIDTH - MARGINS[2], top + PANEL_HEIGHT), (0.0, 4.0), (-1.1, 1.1))
    x = float(panel.x(np.array(2.0)))
    assert _colour_near(both, x, float(panel.y(np.array(1.0))), JOINT_COLOURS[0])
    assert _colour_near(both, x, float(panel.y(np.array(-1.0))), JOINT_COLOURS[1])


def test_a_plan_without_motion_still_gets_a_picture() -> None:
    picture = draw_joint_picture(np.zeros(0), np.zeros((0, 0)), "nothing", [], [])
    middle = np.asarray(picture)[MARGINS[1] + PANEL_HEIGHT // 2 - 8 : MARGINS[1] + PANEL_HEIGHT // 2 + 8]
    assert (middle < 128).any()  # the words saying there is no motion
