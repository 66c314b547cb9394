"""Running one task: ``final_project.py`` in its own process, with a timeout, and its report read back.

The run is a subprocess (its own interpreter and PyBullet client), so a crash,
a hang or a leak in one task cannot touch another. On timeout the whole
process group is killed. The result carries the report's contents, not just
its path, so a task run on another machine (Ray) returns everything the
driver needs to write its row.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from kitchen_tamp.evaluate.grid import TaskSpec

REPORT_FILE = "report.json"
"""Written by ``final_project.py`` into its ``--out`` folder."""
FINAL_PROJECT_MODULE = "kitchen_tamp.cli.final_project"
"""The module behind ``final_project.py`` and ``kitchen-tamp``: found wherever the package is installed."""
STDERR_TAIL_CHARS = 400
"""How much of a crashed run's stderr its result keeps."""
KILL_GRACE_S = 5.0


def default_run_command() -> tuple[str, ...]:
    """``python -m kitchen_tamp.cli.final_project`` (what ``final_project.py`` and ``kitchen-tamp``
    run), so every row can be rerun by hand, from a checkout or from an installed wheel."""
    return (sys.executable, "-m", FINAL_PROJECT_MODULE)


@dataclass(frozen=True)
class RunSettings:
    """How every task of a sweep runs: the command (arguments are appended), timeout, options."""

    command: tuple[str, ...]
    timeout_s: float
    runs_dir: Path
    extra_arguments: tuple[str, ...] = ()

    def arguments(self, task: TaskSpec) -> list[str]:
        """The full command line of ``task``."""
        return [
            *self.command, task.mode, "--problem", str(task.problem), "--seed", str(task.seed),
            "--no-video", "--out", str(self.runs_dir / task.task_id), *self.extra_arguments,
        ]


@dataclass(frozen=True)
class TaskResult:
    """What became of one task: how its process ended and the report it left, if any."""

    task: TaskSpec
    exit_code: int | None
    """None when the task was killed at its timeout; negative for a signal."""
    timed_out: bool
    wall_s: float
    report: dict[str, Any] | None
    stderr_tail: str
    run_dir: Path


class _LiveProcesses:
    """Task processes still running in this interpreter, so an interrupted sweep can stop them."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._processes: set[subprocess.Popen[bytes]] = set()

    def add(self, process: subprocess.Popen[bytes]) -> None:
        with self._lock:
            self._processes.add(process)

    def discard(self, process: subprocess.Popen[bytes]) -> None:
        with self._lock:
            self._processes.discard(process)

    def kill_all(self) -> None:
        with self._lock:
            for process in self._processes:
                _kill_group(process)


LIVE_PROCESSES = _LiveProcesses()


def _kill_group(process: subprocess.Popen[bytes]) -> None:
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        process.kill()


def _read_report(path: Path) -> dict[str, Any] | None:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


def run_task(task: TaskSpec, settings: RunSettings) -> TaskResult:
    """Run ``task`` to its end or its timeout; never raises for anything the task does."""
    run_dir = settings.runs_dir / task.task_id
    report_path = run_dir / REPORT_FILE
    report_path.unlink(missing_ok=True)  # a crash must not leave an older report behind
    run_dir.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    with (run_dir / "stdout.txt").open("wb") as stdout, (run_dir / "stderr.txt").open("wb+") as stderr:
        try:
            process = subprocess.Popen(
                settings.arguments(task), stdout=stdout, stderr=stderr, stdin=subprocess.DEVNULL,
                start_new_session=True,
            )
        except OSError as error:
            return TaskResult(task, None, False, 0.0, None, f"cannot start the run: {error}", run_dir)
        LIVE_PROCESSES.add(process)
        timed_out = False
        try:
            exit_code: int | None = process.wait(timeout=settings.timeout_s)
        except subprocess.TimeoutExpired:
            timed_out = True
            _kill_group(process)
            process.wait(timeout=KILL_GRACE_S)
            exit_code = None
        finally:
            LIVE_PROCESSES.discard(process)
        wall_s = time.perf_counter() - started
        stderr.seek(0)
        tail = stderr.read().decode("utf-8", errors="replace").strip()[-STDERR_TAIL_CHARS:]
    report = None if timed_out else _read_report(report_path)
    return TaskResult(task, exit_code, timed_out, wall_s, report, tail, run_dir)
