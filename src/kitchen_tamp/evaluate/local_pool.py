"""Running tasks on this machine: at most ``workers`` task processes at a time.

Each task is already its own process (``task_run``), so the pool only has to
keep ``workers`` of them going: a thread per slot starts one and waits for it.
Results come back in the order tasks finish.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait

from kitchen_tamp.evaluate.grid import TaskSpec
from kitchen_tamp.evaluate.task_run import LIVE_PROCESSES, RunSettings, TaskResult, run_task


def available_cores() -> int:
    """Cores this process may run on (the local pool's default size)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def run_locally(tasks: Sequence[TaskSpec], settings: RunSettings, workers: int) -> Iterator[TaskResult]:
    """Yield each task's result as it finishes; stopping early (or Ctrl-C) kills the running ones."""
    with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="sweep-task") as pool:
        pending: set[Future[TaskResult]] = {pool.submit(run_task, task, settings) for task in tasks}
        try:
            while pending:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    yield future.result()
        finally:
            for future in pending:
                future.cancel()
            LIVE_PROCESSES.kill_all()
