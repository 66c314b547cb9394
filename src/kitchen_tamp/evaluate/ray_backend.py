"""Running tasks as Ray tasks: on an in-process instance (``local``) or an existing cluster.

Ray is imported only here, and only when a sweep asks for it (``pip install
'.[cluster]'``). Each Ray task still runs ``final_project.py`` as a subprocess
(``task_run.run_task``), so runs stay as isolated as on the local pool; the
Ray worker returns the whole result, report included, to the driver. On a
cluster of several machines, kitchen_tamp must be installed at the same path
on every node and the sweep folder must be on a shared filesystem.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any

from kitchen_tamp.evaluate.grid import TaskSpec
from kitchen_tamp.evaluate.task_run import RunSettings, TaskResult, run_task

LOCAL = "local"
"""``--ray local``: start a Ray instance inside this process, sized to ``--workers``."""


class RayUnavailableError(Exception):
    """Ray is not installed, or the cluster cannot be reached."""


def _import_ray() -> Any:
    try:
        import ray
    except ImportError:
        raise RayUnavailableError(
            "--ray needs the 'ray' package: pip install 'kitchen_tamp[cluster]' (or pip install ray)"
        ) from None
    return ray


def _start(ray: Any, address: str, workers: int) -> None:
    options: dict[str, Any] = {"include_dashboard": False, "log_to_driver": False, "logging_level": "ERROR"}
    try:
        if address == LOCAL:
            ray.init(num_cpus=workers, **options)
        else:
            ray.init(address=address, **options)
    except (ConnectionError, RuntimeError, ValueError) as error:
        first_line = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
        raise RayUnavailableError(f"cannot start Ray at {address!r}: {first_line}") from None


def run_on_ray(
    tasks: Sequence[TaskSpec], settings: RunSettings, address: str, workers: int
) -> Iterator[TaskResult]:
    """Yield each task's result as its Ray task finishes; Ray is shut down afterwards.

    Each task asks Ray for one CPU, so Ray runs as many at once as the cluster
    (or the ``local`` instance, sized to ``workers``) has CPUs.
    """
    ray = _import_ray()
    _start(ray, address, workers)
    try:
        remote_run = ray.remote(num_cpus=1, max_retries=0)(run_task)
        tasks_by_reference = {remote_run.remote(task, settings): task for task in tasks}
        pending = list(tasks_by_reference)
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            for reference in done:
                try:
                    result: TaskResult = ray.get(reference)
                except ray.exceptions.RayError as error:  # the Ray worker itself died
                    task = tasks_by_reference[reference]
                    message = f"Ray task failed: {type(error).__name__}"
                    run_dir = settings.runs_dir / task.task_id
                    result = TaskResult(task, None, False, 0.0, None, message, run_dir)
                yield result
    finally:
        ray.shutdown()
