"""Both judges following a planning run: each step judged as soon as the planner accepts it.

The judges need nothing of the planner but the steps it writes into the file, and
SeSamE accepts a plan's steps one after another, so a forked child judges each
accepted step at once in its own fresh kitchen (the kinematic judge,
``TrajectoryJudge``) and hands it to physics (``PendingPhysics``, the child's own
child) while the planner refines the next step on the first core. What they judge
is what the file holds: when the file is written, its steps must be the steps
followed, value for value and in order, or the verdicts are not used and the file
is judged as a replay judges it (`FollowingJudge.verdict` returns None).

A step the planner takes back (it backtracked, or turned to another abstract plan)
cannot be unjudged: the child is stopped and a new one judges the steps accepted
since, at most ``MAX_STARTS`` times in a run; after that the run is judged once it
is written. A verdict is the one the judges give the written file in a fresh
process (the same replay, the same physics, from the same steps): a test holds
the two equal.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.queues
import os
import pickle
import signal
import time
import traceback
from dataclasses import dataclass
from multiprocessing.connection import Connection
from typing import Final

import numpy as np

from kitchen_tamp.execute.physics.background_physics import (
    PendingPhysics,
    PhysicsError,
    PhysicsJob,
    PhysicsOutcome,
)
from kitchen_tamp.execute.verification import TrajectoryJudge, Verification
from kitchen_tamp.forked_children import can_fork, next_from_parent
from kitchen_tamp.kitchen import KitchenMap, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Task

MAX_STARTS: Final = 3
"""Children a run may start (the first, and one after each step taken back); a step taken back
after that stops the following, and the written file is judged instead."""

_END: Final = None
"""Put on the queue after the last step."""


class FollowingError(RuntimeError):
    """Judging in the child failed (a bug: the message holds its traceback)."""


@dataclass(frozen=True, eq=False)
class JudgedWhilePlanning:
    """The kinematic judge's verdict on the followed steps, and the seconds the child spent
    judging them."""

    verification: Verification
    seconds: float


def _follow(
    task: Task,
    kitchen_map: KitchenMap,
    physics_job: PhysicsJob | None,
    steps: multiprocessing.queues.Queue[bytes | None],
    sender: Connection,
) -> None:
    """The child: judge each step as it comes and hand it to physics; once the last came, send
    the kinematic verdict, then physics' outcome (or a traceback in place of either)."""
    physics: PendingPhysics | None = None

    def stopped(*_: object) -> None:  # by the planner (a step taken back): physics' child goes too
        if physics is not None:
            physics.cancel()
        os._exit(0)

    signal.signal(signal.SIGTERM, stopped)
    try:
        physics = None if physics_job is None else PendingPhysics(physics_job)
        seconds = 0.0
        with build_kitchen_for_task(task, kitchen_map=kitchen_map, visuals=False) as fresh:  # unseen
            judge = TrajectoryJudge(fresh, task)
            while (item := next_from_parent(steps)) is not _END:
                clock = time.perf_counter()
                step: ActionTrajectory = pickle.loads(item)
                judged = judge.judge(step)
                if physics is not None:
                    physics.judged(step, judged)
                seconds += time.perf_counter() - clock
            sender.send(JudgedWhilePlanning(judge.finish(), seconds))
        sender.send(None if physics is None else physics.result())
    except BaseException:  # whatever it was, the parent reports it
        if physics is not None:
            physics.cancel()
        sender.send(traceback.format_exc())
    finally:
        sender.close()


def _same_step(a: ActionTrajectory, b: ActionTrajectory) -> bool:
    """Whether two steps hold the same decisions, value for value."""
    return a is b or (a.action == b.action and len(a.segments) == len(b.segments) and all(
        x.name == y.name and np.array_equal(x.configurations, y.configurations)
        and np.array_equal(x.gripper_widths, y.gripper_widths)
        for x, y in zip(a.segments, b.segments, strict=True)))


class _Child:
    """One forked child following the steps handed to it."""

    def __init__(self, task: Task, kitchen_map: KitchenMap, physics_job: PhysicsJob | None) -> None:
        context = multiprocessing.get_context("fork")
        self.steps: multiprocessing.queues.Queue[bytes | None] = context.Queue()
        self.steps.cancel_join_thread()  # a stopped child reads no more
        self.receiver, sender = context.Pipe(duplex=False)
        # not a daemon: it starts physics' own child; it ends with its last message
        self.process = context.Process(target=_follow,
                                       args=(task, kitchen_map, physics_job, self.steps, sender))
        self.process.start()
        sender.close()

    def receive(self) -> object:
        try:
            return self.receiver.recv()
        except EOFError:
            self.process.join()
            return f"the process judging the plan ended with exit code {self.process.exitcode}"

    def stop(self) -> None:
        if self.process.is_alive():
            self.process.terminate()
        self.process.join()
        self.receiver.close()
        self.steps.close()


class FollowingJudge:
    """Judges a planning run's steps, both judges, in a forked child as they are accepted
    (see the module's docstring). ``physics_job`` None: the kinematic judge only."""

    def __init__(self, task: Task, kitchen_map: KitchenMap, physics_job: PhysicsJob | None) -> None:
        """Starts the child at once: it builds its kitchens while the planner gets ready."""
        self.task, self.kitchen_map, self.physics_job = task, kitchen_map, physics_job
        self.starts = 1
        self._plan: int | None = None
        self._followed: list[ActionTrajectory] = []
        self._child: _Child | None = _Child(task, kitchen_map, physics_job)

    @staticmethod
    def available() -> bool:
        """Whether this platform forks (following needs it)."""
        return can_fork()

    @property
    def following(self) -> bool:
        """Whether a child follows the accepted steps (False once it gave up or was stopped)."""
        return self._child is not None

    def accepted(self, plan: int, index: int, step: ActionTrajectory) -> None:
        """The planner accepted ``step`` as step ``index`` (from 0) of its abstract plan ``plan``."""
        if self._child is None:
            return
        kept = index if plan == self._plan else 0  # the steps followed that still stand
        if kept > len(self._followed):  # a step never seen: nothing to follow
            self.cancel()
            return
        self._plan = plan
        if kept < len(self._followed):  # taken back: judged by a child that has not seen them
            self._stop_child()
            del self._followed[kept:]
            if self.starts == MAX_STARTS:
                return  # given up: the written file is judged instead
            self.starts += 1
            self._child = _Child(self.task, self.kitchen_map, self.physics_job)
            for before in self._followed:
                self._child.steps.put(pickle.dumps(before))
        assert self._child is not None
        self._followed.append(step)
        self._child.steps.put(pickle.dumps(step))  # here, so that what does not pickle raises here

    def verdict(self, trajectory: KitchenTrajectory) -> JudgedWhilePlanning | None:
        """The kinematic judge's verdict if its child followed exactly ``trajectory``'s steps, value
        for value (then `physics` gives physics' outcome); None otherwise (the child is stopped)."""
        child = self._child
        same = len(self._followed) == len(trajectory.steps) and all(
            _same_step(followed, step)
            for followed, step in zip(self._followed, trajectory.steps, strict=True))
        if child is None or not same:
            self.cancel()
            return None
        child.steps.put(_END)
        message = child.receive()
        if isinstance(message, JudgedWhilePlanning):
            if self.physics_job is None:  # the child's last message says it is done
                child.receive()
                self._stop_child()
            return message
        self.cancel()
        raise FollowingError(f"judging the plan as it was refined failed: {message}")

    def physics(self) -> PhysicsOutcome:
        """After `verdict`: physics' outcome on the same steps (of a judge given a physics job)."""
        child = self._child
        if child is None or self.physics_job is None:
            raise RuntimeError("physics' outcome asked of a judge that gave no verdict or executes nothing")
        message = child.receive()
        self._child = None
        child.stop()
        if isinstance(message, PhysicsOutcome):
            return message
        raise PhysicsError(str(message))

    def cancel(self) -> None:
        """Stops following (nothing the child does is written to a file)."""
        self._stop_child()

    def _stop_child(self) -> None:
        if self._child is not None:
            self._child.stop()
            self._child = None
