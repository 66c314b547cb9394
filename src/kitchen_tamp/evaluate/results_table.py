"""``results.csv``: one row per finished task, appended and flushed as tasks finish.

An interrupted sweep keeps every row it wrote; a row cut off mid-write is
dropped when the table is opened again, and ``finished_task_ids`` tells
``--resume`` what not to run twice.
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any, TextIO

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.evaluate.task_run import TaskResult

RESULTS_FILE = "results.csv"
PHASES = (
    "startup_s", "symbolic_s", "refinement_s", "skills_s", "motion_s", "verification_s", "physics_s",
    "rendering_s", "total_s",
)
"""Per-phase seconds copied from the report's ``timing`` (empty when the run has no such phase)."""
COLUMNS = (
    "task_id", "problem", "mode", "seed", "status", "exit_code", "solved", "verified", "collision_free",
    "physics_verified", "failure_stage", "failure_reason", "plan_length", "abstract_plans_tried",
    "samples", "backtracks", "facts_learned", "path_length_rad", "min_clearance_m", "wall_s", *PHASES,
    "problem_path", "run_dir",
)
STATUSES = ("solved", "failed", "timeout", "crashed", "bad_input")
"""``failed``: the run ended normally without a verified solution; ``crashed``: it died or wrote no
report; ``bad_input``: ``final_project.py`` rejected its input (exit 2)."""
BAD_INPUT_EXIT = 2


class ResultsTableError(Exception):
    """An existing ``results.csv`` that is not a results table of this version."""


def status_of(result: TaskResult) -> str:
    """One word for how the task ended (see ``STATUSES``)."""
    if result.timed_out:
        return "timeout"
    if result.exit_code == BAD_INPUT_EXIT:
        return "bad_input"
    if result.report is None or result.exit_code is None or result.exit_code not in (0, 1):
        return "crashed"
    return "solved" if result.exit_code == 0 and result.report.get("solved") is True else "failed"


def _flag(value: object) -> str:
    return "" if value is None else str(bool(value)).lower()


def _section(report: Mapping[str, Any], key: str) -> Mapping[str, Any]:
    value = report.get(key)
    return value if isinstance(value, Mapping) else {}


def _path_length(report: Mapping[str, Any]) -> str:
    lengths = [
        step["motion"]["path_length_rad"] for step in report.get("steps") or []
        if isinstance(step, Mapping) and isinstance(step.get("motion"), Mapping)
        and isinstance(step["motion"].get("path_length_rad"), int | float)
    ]
    return f"{sum(lengths):.4f}" if lengths else ""


def _one_line(text: str) -> str:
    return " ".join(text.split())


def row_of(result: TaskResult) -> dict[str, str]:
    """The CSV row of a finished task; fields the run did not report are left empty."""
    report: Mapping[str, Any] = result.report or {}
    verification = _section(report, "verification")
    physics = _section(report, "physics")
    failure = _section(report, "failure")
    bilevel = _section(report, "bilevel")
    timing = _section(report, "timing")
    status = status_of(result)
    reason = str(failure.get("reason") or "")
    if status == "timeout":
        reason = f"no result within {result.wall_s:.0f} s"
    elif status in ("crashed", "bad_input"):
        reason = result.stderr_tail.splitlines()[-1] if result.stderr_tail else f"exit {result.exit_code}"
    plan = report.get("plan")
    row = {
        "task_id": result.task.task_id,
        "problem": result.task.problem_name,
        "mode": result.task.mode,
        "seed": str(result.task.seed),
        "status": status,
        "exit_code": "" if result.exit_code is None else str(result.exit_code),
        "solved": _flag(report.get("solved")) if report else "false",
        "verified": _flag(verification.get("verified")),
        "collision_free": _flag(verification.get("collision_free")),
        "physics_verified": _flag(physics.get("verified")),
        "failure_stage": str(failure.get("stage") or "") if status == "failed" else status,
        "failure_reason": _one_line(reason) if status != "solved" else "",
        "plan_length": str(len(plan)) if isinstance(plan, list) else "",
        "abstract_plans_tried": str(bilevel.get("abstract_plans_tried", "")),
        "samples": str(bilevel.get("samples", "")),
        "backtracks": str(bilevel.get("backtracks", "")),
        "facts_learned": str(len(bilevel.get("learned") or [])) if bilevel else "",
        "path_length_rad": _path_length(report),
        "min_clearance_m": str(verification.get("min_clearance_m", "")),
        "wall_s": f"{result.wall_s:.3f}",
        "problem_path": str(result.task.problem),
        "run_dir": str(result.run_dir),
    }
    for phase in PHASES:
        value = timing.get(phase)
        row[phase] = f"{value:.4f}" if isinstance(value, int | float) else ""
    if status == "solved":
        row["failure_stage"] = ""
    return row


def read_rows(path: Path) -> list[dict[str, str]]:
    """The complete rows of a results table: a last line cut off by an interruption is left out."""
    if not path.exists():
        return []
    text = path.read_text(encoding="utf-8")
    if not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
    reader = csv.DictReader(io.StringIO(text))
    if text and tuple(reader.fieldnames or ()) != COLUMNS:
        raise ResultsTableError(f"{path}: not a results table of this version (its columns differ)")
    return [
        {str(key): str(value) for key, value in row.items()}
        for row in reader
        if None not in row and None not in row.values()
    ]


class ResultsTable:
    """An open ``results.csv``: ``append`` writes and flushes one row; ``task_ids`` are the rows so far."""

    def __init__(self, path: Path, resume: bool) -> None:
        self.path = path
        rows = read_rows(path) if resume else []
        unique = {row["task_id"]: row for row in rows}
        self.task_ids = set(unique)
        buffer = io.StringIO()
        writer = csv.DictWriter(buffer, COLUMNS, lineterminator="\n")
        writer.writeheader()
        writer.writerows(unique.values())
        write_atomically(path, buffer.getvalue())
        self._stream: TextIO = path.open("a", newline="", encoding="utf-8")
        self._writer = csv.DictWriter(self._stream, COLUMNS, lineterminator="\n")

    def append(self, row: Mapping[str, str]) -> None:
        if row["task_id"] in self.task_ids:
            return
        self._writer.writerow(row)
        self._stream.flush()
        os.fsync(self._stream.fileno())
        self.task_ids.add(row["task_id"])

    def close(self) -> None:
        self._stream.close()

    def __enter__(self) -> ResultsTable:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()
