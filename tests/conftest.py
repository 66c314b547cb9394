"""Fixtures shared by the whole suite: kitchen runs planned once per test session.

``kitchen_runs`` hands out, per (problem, mode, seed), the refined trajectory
(``refined``: SeSamE in a fresh kitchen, no judging) or a whole
``final_project.py`` run directory (``run_dir``: planned, judged, its files
written). Each is planned the first time a test asks for it and kept for the
session; tests that doctor a run copy its files first.
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass, replace
from pathlib import Path

import pytest

from kitchen_tamp.execute import SavedRun
from kitchen_tamp.execute.run_inputs import RunInputs
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task, load_task
from kitchen_tamp.refinement import MotionBackend, SamplingMotionBackend, refine_with_sesame
from kitchen_tamp.refinement.optimizing_backend import OptimizingMotionBackend
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from kitchen_tamp.shipped_kitchens import default_scene_path

REPO = Path(__file__).resolve().parents[1]
PDDL = REPO / "pddl"
DOMAIN = PDDL / "domain.pddl"


@dataclass(frozen=True, eq=False)
class PlannedRun:
    """A kitchen problem refined by SeSamE with one motion back end and seed."""

    problem: Path
    mode: str
    seed: int
    task: Task
    trajectory: KitchenTrajectory

    def saved(self, trajectory: KitchenTrajectory | None = None) -> SavedRun:
        """The run as ``final_project.py`` saves it (with its files' digests); with
        ``trajectory``, that trajectory in its place."""
        scene = default_scene_path()
        inputs = RunInputs.of({"problem": self.problem, "domain": DOMAIN, "scene": scene})
        run = SavedRun(self.problem, DOMAIN, self.mode, self.seed, self.trajectory, scene=scene,
                       sha256=inputs.digests())
        return run if trajectory is None else replace(run, trajectory=trajectory)


def _backend(mode: str) -> MotionBackend:
    return OptimizingMotionBackend(DEFAULT_SETTINGS) if mode == "optimizes" else SamplingMotionBackend()


class KitchenRuns:
    """Refined plans and whole runs, each made once per session."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self._refined: dict[tuple[str, str, int], PlannedRun] = {}
        self._run_dirs: dict[tuple[str, str, int, bool], Path] = {}

    def refined(self, problem: str = "problem.pddl", mode: str = "rrt", seed: int = 0) -> PlannedRun:
        """``pddl/problem`` refined with ``mode``'s back end and ``seed`` (asserted to succeed)."""
        key = (problem, mode, seed)
        if key not in self._refined:
            task = load_task(PDDL / problem, DOMAIN)
            with build_kitchen_for_task(task) as kitchen:
                refined = refine_with_sesame(kitchen, task, _backend(mode), seed=seed).refined
            assert refined is not None, f"{problem} {mode} seed {seed} did not refine"
            self._refined[key] = PlannedRun(PDDL / problem, mode, seed, task, refined.trajectory)
        return self._refined[key]

    def run_dir(
        self, problem: str = "problem.pddl", mode: str = "rrt", seed: int = 0, video: bool = False
    ) -> Path:
        """The folder of ``final_project.py MODE --problem pddl/PROBLEM --seed SEED`` (with the
        pictures when ``video``), asserted to exit 0. Do not change it: copy it."""
        from kitchen_tamp.cli.final_project import main

        key = (problem, mode, seed, video)
        if key not in self._run_dirs:
            out = self.folder / f"{Path(problem).stem}-{mode}-{seed}{'-video' if video else ''}"
            argv = [mode, "--problem", str(PDDL / problem), "--seed", str(seed), "--out", str(out)]
            assert main(argv + ([] if video else ["--no-video"])) == 0
            self._run_dirs[key] = out
        return self._run_dirs[key]

    def copy_of(self, run_dir: Path, into: Path) -> Path:
        """A copy of a run folder's files, to doctor."""
        shutil.copytree(run_dir, into)
        return into


@pytest.fixture(scope="session")
def kitchen_runs(tmp_path_factory: pytest.TempPathFactory) -> KitchenRuns:
    return KitchenRuns(tmp_path_factory.mktemp("kitchen_runs"))
