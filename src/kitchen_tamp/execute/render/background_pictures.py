"""``replay.gif`` (or, without it, ``joints.png``) drawn on the second core while the run goes on.

Both pictures need only the kinematic judge's timeline, so once the judge has
given it, a forked child process draws the GIF (building its own kitchen), while
the parent executes the run under physics and writes replay.html and joints.png:
that splits the work about evenly. Without a GIF, the child draws joints.png
while the parent runs physics.
The child inherits what it needs (the task, the kitchen map, the timeline) by
the fork and sends back what it wrote, or the traceback of what went wrong.
Where processes cannot be forked, the pictures are drawn in this process when
their result is asked for.
"""

from __future__ import annotations

import multiprocessing
import time
import traceback
from dataclasses import dataclass
from multiprocessing.connection import Connection
from pathlib import Path

from kitchen_tamp.execute.render.joint_plot import plot_joints
from kitchen_tamp.execute.render.replay_video import FRAME_SECONDS, render_replay, write_gif
from kitchen_tamp.execute.timeline import Timeline
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
    timeline: Timeline
    out_dir: Path
    joints_title: str
    velocities: bool = False
    """Plot joint velocities below the angles (``optimizes``)."""
    gif: bool = True
    """Render ``replay.gif``."""
    joints: bool = True
    """Plot ``joints.png`` (else whoever holds the job does, with `draw_joints`)."""

    def draw_joints(self) -> tuple[Path, float]:
        """Plots ``joints.png``: its path and the seconds it took."""
        clock = time.perf_counter()
        path = plot_joints(self.timeline, self.joints_title, self.out_dir / JOINTS_FILE, self.velocities)
        return path, time.perf_counter() - clock

    def run(self) -> Pictures:
        joints, joints_s = self.draw_joints() if self.joints else (None, 0.0)
        if not self.gif:
            return Pictures(joints, joints_s)
        clock = time.perf_counter()
        with build_kitchen_for_task(self.task, kitchen_map=self.kitchen_map) as kitchen:
            images = render_replay(kitchen, self.timeline)
        gif = write_gif(self.out_dir / GIF_FILE, images, FRAME_SECONDS) if images else None
        return Pictures(joints, joints_s, gif, len(images), time.perf_counter() - clock)


def _draw_in_child(job: PictureJob, sender: Connection) -> None:
    try:
        sender.send(job.run())
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
        if "fork" in multiprocessing.get_all_start_methods():
            context = multiprocessing.get_context("fork")
            self._receiver, sender = context.Pipe(duplex=False)
            self._process = context.Process(target=_draw_in_child, args=(job, sender), daemon=True)
            self._process.start()
            sender.close()

    def result(self) -> Pictures:
        """Waits for the pictures; raises `PictureError` with the child's traceback if it failed."""
        if self._process is None or self._receiver is None:
            return self.job.run()
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
        self._process = self._receiver = None
