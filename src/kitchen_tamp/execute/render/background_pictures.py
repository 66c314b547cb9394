"""``replay.gif`` (or, without it, ``joints.png``) drawn on the second core while the run goes on.

Both pictures need only the kinematic judge's timeline, so once the judge has
given it, a forked child process draws the GIF (building its own kitchen), while
the parent waits for physics and writes replay.html and joints.png: that splits
the work about evenly. Without a GIF, the child draws joints.png.
The child inherits what it needs (the task, the kitchen map and, if known, the
timeline) by the fork and sends back what it wrote, or the traceback of what went
wrong. A job without a timeline starts the child at once: it builds its kitchen and
what the GIF's frames need before the timeline (`ReplayRenderer`: the camera, the
robot's stand-ins, the still background) while the judge reads the plan, then waits
for the timeline (`PendingPictures.draw`).
Where processes cannot be forked, the pictures are drawn in this process when
their result is asked for.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.queues
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from multiprocessing.connection import Connection
from pathlib import Path

from kitchen_tamp.execute.timeline import Timeline
from kitchen_tamp.forked_children import can_fork, next_from_parent
from kitchen_tamp.kitchen import KitchenMap, build_kitchen_for_task
from kitchen_tamp.planning import Task

GIF_FILE = "replay.gif"
JOINTS_FILE = "joints.png"


class PictureError(RuntimeError):
    """Drawing the pictures failed in the child (a bug: the message holds its traceback)."""


@dataclass(frozen=True)
class Pictures:
    """What was drawn: the files (the GIF None when not asked for or without frames), the GIF's
    frame count, and the seconds each took."""

    joints: Path | None = None
    joints_s: float = 0.0
    gif: Path | None = None
    frames: int = 0
    gif_s: float = 0.0


@dataclass(frozen=True)
class PictureJob:
    """What the pictures are made from and where they go."""

    task: Task
    kitchen_map: KitchenMap
    timeline: Timeline | None
    """The judge's timeline, or None when it is handed over later (`PendingPictures.draw`)."""
    out_dir: Path
    joints_title: str
    velocities: bool = False
    """Plot joint velocities below the angles (``optimizes``)."""
    gif: bool = True
    """Render ``replay.gif``."""
    joints: bool = True
    """Plot ``joints.png`` (else whoever holds the job does, with `draw_joints`)."""

    def draw_joints(self, timeline: Timeline | None = None) -> tuple[Path, float]:
        """Plots ``joints.png`` (of ``timeline``, else the job's): its path and the seconds it took."""
        clock = time.perf_counter()
        timeline = timeline or self.timeline
        if timeline is None:
            raise ValueError("no timeline to plot")
        from kitchen_tamp.execute.render.joint_plot import plot_joints  # PIL: only where it draws

        path = plot_joints(timeline, self.joints_title, self.out_dir / JOINTS_FILE, self.velocities)
        return path, time.perf_counter() - clock

    def run(self, timeline_of: Callable[[], Timeline] | None = None) -> Pictures:
        """Draws the pictures of the job's timeline, else of ``timeline_of()``, asked for once
        what can be done without it is done."""
        from kitchen_tamp.execute.render.joint_plot import load_plotting  # PIL: only where it draws
        from kitchen_tamp.execute.render.replay_video import FRAME_SECONDS, ReplayRenderer, write_gif

        if self.joints:
            load_plotting()

        def timeline() -> Timeline:
            if self.timeline is not None:
                return self.timeline
            if timeline_of is None:
                raise ValueError("no timeline to draw")
            return timeline_of()

        if not self.gif:
            return Pictures(*self.draw_joints(timeline()))
        with build_kitchen_for_task(self.task, kitchen_map=self.kitchen_map) as kitchen:
            renderer = ReplayRenderer(kitchen)
            drawn = timeline()
            joints, joints_s = self.draw_joints(drawn) if self.joints else (None, 0.0)
            clock = time.perf_counter()
            images = renderer.images(drawn)
        gif = write_gif(self.out_dir / GIF_FILE, images, FRAME_SECONDS) if images else None
        return Pictures(joints, joints_s, gif, len(images), time.perf_counter() - clock)


def _draw_in_child(
    job: PictureJob, timelines: multiprocessing.queues.Queue[Timeline] | None, sender: Connection
) -> None:
    try:
        timeline_of = None if timelines is None else partial(next_from_parent, timelines)
        sender.send(job.run(timeline_of))
    except BaseException:  # whatever it was, the parent reports it
        sender.send(traceback.format_exc())
    finally:
        sender.close()


class PendingPictures:
    """Pictures being drawn: in a forked child when the platform forks, else on ``result()``."""

    def __init__(self, job: PictureJob) -> None:
        self.job = job
        self._process: multiprocessing.process.BaseProcess | None = None
        self._receiver: Connection | None = None
        self._timelines: multiprocessing.queues.Queue[Timeline] | None = None
        self._timeline: Timeline | None = job.timeline
        if can_fork():
            context = multiprocessing.get_context("fork")
            self._receiver, sender = context.Pipe(duplex=False)
            if job.timeline is None:
                self._timelines = context.Queue()
                self._timelines.cancel_join_thread()  # a cancelled child reads nothing
            self._process = context.Process(target=_draw_in_child, args=(job, self._timelines, sender),
                                            daemon=True)
            self._process.start()
            sender.close()

    def draw(self, timeline: Timeline) -> None:
        """Hands over the timeline of a job made without one (without waiting for the child to
        take it)."""
        self._timeline = timeline
        if self._timelines is not None:
            self._timelines.put(timeline)

    def _timeline_here(self) -> Timeline:
        if self._timeline is None:
            raise ValueError("no timeline was handed over")
        return self._timeline

    def result(self) -> Pictures:
        """Waits for the pictures; raises `PictureError` with the child's traceback if it failed."""
        if self._process is None or self._receiver is None:
            return self.job.run(self._timeline_here)
        try:
            outcome = self._receiver.recv()
        except EOFError:
            outcome = f"the process drawing the pictures ended with exit code {self._process.exitcode}"
        finally:
            self._process.join()
            self._receiver.close()
        if isinstance(outcome, Pictures):
            return outcome
        raise PictureError(str(outcome))

    def cancel(self) -> None:
        """Stops the child; what it was writing is removed (files are written to a temporary name
        with the writer's process id, then renamed: see `kitchen_tamp.atomic_files`)."""
        if self._process is not None and self._process.is_alive():
            self._process.terminate()
            self._process.join()
            for unfinished in self.job.out_dir.glob(f".*.{self._process.pid}.*.tmp"):
                unfinished.unlink(missing_ok=True)
        if self._receiver is not None:
            self._receiver.close()
        if self._timelines is not None:
            self._timelines.close()
        self._process = self._receiver = self._timelines = None
