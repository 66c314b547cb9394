"""A sweep from start to end: tasks not yet in ``results.csv`` run on the chosen backend, each row
is written as its task finishes, and the summary and plots are made from the whole table."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

from kitchen_tamp.evaluate.grid import TaskSpec
from kitchen_tamp.evaluate.local_pool import run_locally
from kitchen_tamp.evaluate.progress import SweepProgress
from kitchen_tamp.evaluate.results_table import RESULTS_FILE, ResultsTable, read_rows, row_of
from kitchen_tamp.evaluate.task_run import RunSettings, TaskResult

RUNS_DIR = "runs"
"""Each task's ``--out`` folder is ``SWEEP/runs/TASK_ID``."""


@dataclass(frozen=True)
class SweepPlan:
    """Everything a sweep needs to run: its tasks, where it writes, how tasks run and where."""

    tasks: tuple[TaskSpec, ...]
    out_dir: Path
    settings: RunSettings
    workers: int
    ray_address: str | None = None
    resume: bool = False


def _results(plan: SweepPlan, tasks: Sequence[TaskSpec]) -> Iterator[TaskResult]:
    if plan.ray_address is None:
        return run_locally(tasks, plan.settings, plan.workers)
    from kitchen_tamp.evaluate.ray_backend import run_on_ray  # Ray only when asked for

    return run_on_ray(tasks, plan.settings, plan.ray_address, plan.workers)


def run_sweep(plan: SweepPlan) -> list[dict[str, str]]:
    """Run the tasks that have no row yet; the rows of this sweep's tasks, in grid order."""
    with ResultsTable(plan.out_dir / RESULTS_FILE, plan.resume) as table:
        todo = [task for task in plan.tasks if task.task_id not in table.task_ids]
        earlier = [row for row in read_rows(table.path) if row["task_id"] in {t.task_id for t in plan.tasks}]
        failed_earlier = sum(row["status"] != "solved" for row in earlier)
        progress = SweepProgress(len(plan.tasks), len(plan.tasks) - len(todo), failed_earlier)
        try:
            if todo:
                for result in _results(plan, todo):
                    row = row_of(result)
                    table.append(row)
                    progress.task_done(row["status"] == "solved")
        finally:
            progress.close()
    order = {task.task_id: index for index, task in enumerate(plan.tasks)}
    rows = [row for row in read_rows(plan.out_dir / RESULTS_FILE) if row["task_id"] in order]
    return sorted(rows, key=lambda row: order[row["task_id"]])
