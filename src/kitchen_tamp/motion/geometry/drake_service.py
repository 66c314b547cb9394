"""Drake's collision models in a process of their own, which loads Drake while the planner starts.

The sphere model in front of Drake's (`spheres.screening`) decides most configurations
alone, but near a grasp it defers to Drake, and the first deferral of a run costs
loading Drake (about 0.15 s of CPU) and building the world's model (about 0.05 s).
A `DrakeService` forks a process that loads Drake at once, on the second core, while
the planner imports the rest, reads the problem and samples its first steps; the
planner then hands it a world's scene description the first time that world defers,
and configurations to decide, and gets Drake's verdicts back. It is the same library
with the same inputs, so the verdicts are the ones an in-process model gives
(tests/motion/test_drake_service.py holds the two equal).

Requests are answered in order on one pipe; a model is built on its world's first
question. The service ends when the planner closes it, or when the planner's process is
gone.
"""

from __future__ import annotations

import contextlib
import itertools
import multiprocessing
import traceback
from multiprocessing.connection import Connection
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from kitchen_tamp.forked_children import PARENT_CHECK_S, can_fork, received_from_parent
from kitchen_tamp.motion.collision_checker import JointConfigurations, ValidityMask

if TYPE_CHECKING:
    from kitchen_tamp.motion.geometry.described_scene import DescribedScene
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker

class DrakeServiceError(RuntimeError):
    """The service failed to answer (a bug, or a scene Drake cannot load: the message says which)."""


def _serve(connection: Connection, planner_end: Connection) -> None:
    """The service: load Drake, then answer ``("build", key, scene, margin)`` (no answer) and
    ``("is_valid", key, configurations)`` (the verdicts, or a traceback) until ``None`` or EOF."""
    scenes: dict[int, tuple[DescribedScene, float]] = {}
    models: dict[int, DrakeCollisionChecker] = {}
    try:
        planner_end.close()  # so that the pipe ends with the planner
        from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker  # loads Drake, now

        while (request := received_from_parent(connection)) is not None:
            kind, key, *arguments = cast(tuple[Any, ...], request)
            if kind == "build":
                scene, margin = arguments
                scenes[key] = (scene, margin)
                continue
            try:
                if key not in models:
                    scene, margin = scenes.pop(key)
                    models[key] = DrakeCollisionChecker(scene, margin=margin)
                connection.send(models[key].is_valid(arguments[0]))
            except Exception:  # the planner raises it
                connection.send(traceback.format_exc())
    except (EOFError, KeyboardInterrupt):  # the planner is gone, or Ctrl-C (the planner says so)
        pass
    finally:
        connection.close()


class DrakeService:
    """A process answering Drake's validity verdicts for the planner (see the module's docstring)."""

    def __init__(self) -> None:
        context = multiprocessing.get_context("fork")
        self._connection, served = context.Pipe()
        self._process = context.Process(target=_serve, args=(served, self._connection), daemon=True)
        self._process.start()
        served.close()
        self._keys = itertools.count()

    @staticmethod
    def available() -> bool:
        """Whether this platform forks (the service needs it)."""
        return can_fork()

    def model(self, scene: DescribedScene, margin: float) -> RemoteDrakeModel:
        """Drake's model of ``scene`` keeping ``margin``, built in the service on its first question."""
        key = next(self._keys)
        self._connection.send(("build", key, scene, float(margin)))
        return RemoteDrakeModel(self, key)

    def is_valid(self, key: int, qs: JointConfigurations) -> ValidityMask:
        self._connection.send(("is_valid", key, np.ascontiguousarray(qs, dtype=float)))
        try:
            answer = self._connection.recv()
        except EOFError:
            answer = f"the process holding Drake's models ended with exit code {self._process.exitcode}"
        if isinstance(answer, np.ndarray):
            return answer
        raise DrakeServiceError(str(answer))

    def close(self) -> None:
        """Ends the service (its models with it)."""
        if self._process.is_alive():
            with contextlib.suppress(OSError):  # it ended already
                self._connection.send(None)
            self._process.join(timeout=PARENT_CHECK_S)
            if self._process.is_alive():
                self._process.terminate()
                self._process.join()
        self._connection.close()


class RemoteDrakeModel:
    """One world's Drake model in a `DrakeService`: its validity verdicts."""

    def __init__(self, service: DrakeService, key: int) -> None:
        self._service, self._key = service, key

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        return self._service.is_valid(self._key, np.atleast_2d(np.asarray(qs, dtype=float)))
