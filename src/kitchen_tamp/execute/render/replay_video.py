"""``replay.gif``: the whole task seen from a camera that shows the counter and the drawer."""

from __future__ import annotations

import io
from collections.abc import Callable
from pathlib import Path

import imageio.v3 as iio
import numpy as np

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.execute.timeline import Timeline
from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.kitchen.show import overview_camera
from kitchen_tamp.world import Image, render

MAX_FRAMES = 120
"""Frames in a GIF at most; long runs are shown faster rather than longer."""
MIN_FRAMES = 40
"""Frames in a GIF at least; short runs are sampled more finely."""
FRAME_SECONDS = 0.1
"""How long each frame shows when the run is played at nominal speed."""


def frame_times(timeline: Timeline, max_frames: int = MAX_FRAMES, min_frames: int = MIN_FRAMES) -> np.ndarray:
    """Evenly spaced times from start to end: one per ``FRAME_SECONDS``, within the frame limits."""
    count = int(np.clip(np.ceil(timeline.duration / FRAME_SECONDS) + 1, min_frames, max_frames))
    return np.linspace(0.0, timeline.duration, count)


def render_replay(
    kitchen: KitchenScene,
    timeline: Timeline,
    width: int = 400,
    height: int = 300,
    on_frame: Callable[[int, int], None] | None = None,
) -> list[Image]:
    """Pictures of ``kitchen`` (built fresh for the problem) along ``timeline``; one picture of
    the scene as it is for a timeline without motion (a plan of no actions)."""
    view = overview_camera(kitchen, width, height)
    if not timeline.segments:
        return [render(kitchen.scene, view)]
    times = frame_times(timeline)
    images = []
    for number, _ in enumerate(timeline.play(kitchen, times)):
        images.append(render(kitchen.scene, view))
        if on_frame is not None:
            on_frame(number + 1, len(times))
    return images


def write_gif(path: Path, images: list[Image], seconds_per_frame: float) -> Path:
    """Encode ``images`` as a looping GIF and write it atomically."""
    buffer = io.BytesIO()
    iio.imwrite(buffer, np.stack(images), extension=".gif", duration=int(1000 * seconds_per_frame), loop=0)
    return write_atomically(path, buffer.getvalue())
