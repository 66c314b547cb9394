"""Execution under physics on the second core, step by step as the kinematic judge reads the plan.

Physics needs of the kinematic judge only what it read in each step (its tracks and
the scene after it: a ``JudgedStep``), and the judge needs nothing of physics, so a
forked child executes the trajectory while the judge reads it: the judge hands
over each step with its reading as soon as it is judged (pickled, on a queue, so
the judge never waits), the child
executes each step once it has it, and sends back its verdict and, when asked, what
it recorded for ``replay.html``. A planning run's re-plan under physics happens in
the child too (its ``Replanner`` is inherited by the fork; only its result comes
back). Where processes cannot be forked, the judged steps are kept and executed in
this process when the result is asked for.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.queues
import pickle
import time
import traceback
from collections.abc import Iterator
from dataclasses import dataclass
from multiprocessing.connection import Connection

from kitchen_tamp.execute.physics.execution import JudgedPair, execute_under_physics
from kitchen_tamp.execute.physics.replanning import Replanner
from kitchen_tamp.execute.physics.verdict import PhysicsExecution
from kitchen_tamp.execute.render.rollout_recording import RecordedRollout, RolloutRecorder
from kitchen_tamp.execute.verification import JudgedStep
from kitchen_tamp.forked_children import can_fork, next_from_parent
from kitchen_tamp.kitchen import KitchenMap
from kitchen_tamp.kitchen.trajectory import ActionTrajectory
from kitchen_tamp.planning import Task


class PhysicsError(RuntimeError):
    """Execution under physics failed in the child (a bug: the message holds its traceback)."""


@dataclass(frozen=True, eq=False)
class PhysicsOutcome:
    """What execution under physics gave: the verdict, what was recorded for the page (None when
    not asked for or nothing was), and the seconds it took where it ran."""

    execution: PhysicsExecution
    recorded: RecordedRollout | None
    seconds: float


@dataclass(frozen=True, eq=False)
class PhysicsJob:
    """What to execute: steps of ``task`` (handed over as judged) in the kitchen of ``kitchen_map``,
    re-planning with ``replan`` if given, recording the rollout for ``replay.html`` if ``record``."""

    task: Task
    kitchen_map: KitchenMap
    replan: Replanner | None
    record: bool

    def run(self, judged: Iterator[JudgedPair]) -> PhysicsOutcome:
        clock = time.perf_counter()
        recorder = RolloutRecorder() if self.record else None
        execution = execute_under_physics(self.task, judged, self.kitchen_map, on_frame=recorder,
                                          replan=self.replan)
        recorded = None if recorder is None else recorder.recorded()
        return PhysicsOutcome(execution, recorded, time.perf_counter() - clock)


_END = None
"""Put on the queue after the last judged step."""


def _queued_steps(steps: multiprocessing.queues.Queue[bytes | None]) -> Iterator[JudgedPair]:
    while (step := next_from_parent(steps)) is not _END:
        yield pickle.loads(step)


def _execute_in_child(
    job: PhysicsJob, steps: multiprocessing.queues.Queue[bytes | None], sender: Connection
) -> None:
    try:
        sender.send(job.run(_queued_steps(steps)))
    except BaseException:  # whatever it was, the parent reports it
        sender.send(traceback.format_exc())
    finally:
        sender.close()


class PendingPhysics:
    """Execution under physics of the steps handed to `judged`, in a forked child when the
    platform forks (else in this process, on ``result()``)."""

    def __init__(self, job: PhysicsJob) -> None:
        self.job = job
        self._kept: list[JudgedPair] = []
        self._process: multiprocessing.process.BaseProcess | None = None
        self._receiver: Connection | None = None
        self._steps: multiprocessing.queues.Queue[bytes | None] | None = None
        if can_fork():
            context = multiprocessing.get_context("fork")
            self._steps = context.Queue()
            self._steps.cancel_join_thread()  # a child that stopped early (a re-plan) reads no more
            self._receiver, sender = context.Pipe(duplex=False)
            self._process = context.Process(target=_execute_in_child, args=(job, self._steps, sender),
                                            daemon=True)
            self._process.start()
            sender.close()

    def judged(self, step: ActionTrajectory, judged: JudgedStep) -> None:
        """Hands over the file's next step and how the kinematic judge read it."""
        if self._steps is None:
            self._kept.append((step, judged))
        else:
            self._steps.put(pickle.dumps((step, judged)))  # here, so that what does not pickle raises here

    def result(self) -> PhysicsOutcome:
        """Once every step was handed over: waits for the verdict; raises `PhysicsError` with the
        child's traceback if it failed."""
        if self._process is None or self._receiver is None or self._steps is None:
            return self.job.run(iter(self._kept))
        self._steps.put(_END)
        try:
            outcome = self._receiver.recv()
        except EOFError:
            outcome = f"the process executing under physics ended with exit code {self._process.exitcode}"
        finally:
            self._process.join()
            self._receiver.close()
            self._steps.close()
        if isinstance(outcome, PhysicsOutcome):
            return outcome
        raise PhysicsError(str(outcome))

    def cancel(self) -> None:
        """Stops the child (nothing it does is written to a file)."""
        if self._process is not None and self._process.is_alive():
            self._process.terminate()
            self._process.join()
        if self._receiver is not None:
            self._receiver.close()
        if self._steps is not None:
            self._steps.close()
        self._process = self._receiver = self._steps = None
