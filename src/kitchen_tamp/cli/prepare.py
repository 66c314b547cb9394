"""``python -m kitchen_tamp.cli.prepare``: compile the sphere model's and the planners' kernels at install.

The validity and clearance kernels are compiled by numba the first time they are
called (about half a minute of one core) and cached on disk beside their sources
(``__pycache__``; where the installed package is read-only, numba keeps them in
the user's cache). ``make install`` runs this once, so that a fresh checkout's
first run spends its time planning rather than compiling; an installed wheel can
run it too (``kitchen-tamp-prepare``). It calls each kernel once, with the argument
types a run gives it, on the default kitchen built in a throw-away cache folder,
so nothing lands in the user's cache (no models, no spheres): their first run
still starts from an empty cache. RRT-Connect's compiled loop runs one iteration on that
kitchen's sphere model. The activity planner's relaxed exploration
(``kitchen_tamp.planning.relaxed_kernel``) and its compiled greedy search
(``kitchen_tamp.planning.search.greedy_kernel``) are compiled the same way, on
the default kitchen's task, and the same search, written in C, with the system's
C compiler into a library that runs without numpy or numba (``native_greedy``). The sphere model's
validity and clearance kernels, which is all a kitchen run calls, are compiled once more ahead of time
(``motion.geometry.spheres.kernels.ahead_of_time``): such a run never imports numba.
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from kitchen_tamp.planning import Task

if TYPE_CHECKING:  # the real import loads numba, which `main` must import before moving the cache
    from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker


def _compile_kernels() -> None:
    from kitchen_tamp.kitchen import build_kitchen_for_task
    from kitchen_tamp.kitchen.scene.choice import choose_scene
    from kitchen_tamp.motion.geometry.spheres import SphereClearance, SphereCollisionChecker
    from kitchen_tamp.motion.geometry.spheres.kernels.loading import serve_jit_kernels
    from kitchen_tamp.planning import load_task
    from kitchen_tamp.shipped_kitchens import DEFAULT_PROBLEM
    from kitchen_tamp.world import describe_collision_checker

    choice = choose_scene(DEFAULT_PROBLEM)
    task = load_task(choice.problem, choice.domain)
    with build_kitchen_for_task(task, kitchen_map=choice.kitchen_map()) as kitchen:
        description = describe_collision_checker(kitchen.collision_checker())
        home = np.atleast_2d(kitchen.arm_configuration())
    serve_jit_kernels()  # into numba's cache, whether or not a module compiled ahead of time serves runs
    checker = SphereCollisionChecker(description)
    checker.is_valid(home)
    checker.is_valid_without_padding(home)
    SphereClearance(checker.model, 0.005, ends=home)(home)
    _compile_rrt_connect_loop(checker, home[0])
    _compile_segments(checker, home[0])
    _compile_shortcut_steps(checker, home[0])
    _compile_sphere_kernels_ahead_of_time(checker, home)
    _compile_planning_kernels(task)


def _compile_sphere_kernels_ahead_of_time(
    checker: SphereCollisionChecker, home: npt.NDArray[np.float64]
) -> None:
    """The validity and clearance kernels into the module a run loads without numba
    (`kernels.loading`), with the signatures of their JIT runs on the default kitchen (the
    clearance's ran above)."""
    from kitchen_tamp.motion.geometry.spheres.kernels.ahead_of_time import (
        compile_ahead_of_time,
        valid_configurations_of_fields,
    )
    from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid import distance_grid_cells
    from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import with_derived

    fields = with_derived(checker.kernel_arguments, distance_grid_cells)
    valid_configurations_of_fields(fields, home, checker.margin, False)
    _ahead_of_time("the sphere model's kernels", compile_ahead_of_time)


def _ahead_of_time(what: str, compile_module: Callable[[], object]) -> None:
    """Compile ``what`` ahead of time, or say why not (the run then uses numba's JIT, the same code)."""
    try:
        compile_module()
    except Exception as error:  # e.g. a read-only install or no C compiler
        reason = " ".join(str(error).split())
        print(f"not compiled ahead of time: {what} ({type(error).__name__}: {reason}); "
              "runs will use numba's JIT, the same code")


def _compile_rrt_connect_loop(checker: SphereCollisionChecker, home: npt.NDArray[np.float64]) -> None:
    """RRT-Connect's compiled calls (`compiled_rrt_connect.compile_loop_kernels`) from ``home``."""
    from kitchen_tamp.motion import ConfigurationSpace
    from kitchen_tamp.motion.sampling.compiled_rrt_connect import LoopQuery, compile_loop_kernels
    from kitchen_tamp.motion.sampling.rrt_connect import RrtConnectHyperparameters

    space = ConfigurationSpace(checker.lower, checker.upper)
    query = LoopQuery(space, 0, RrtConnectHyperparameters(max_iterations=1), math.inf)
    compile_loop_kernels(home, checker.compiled_validity(), query)


def _compile_segments(checker: SphereCollisionChecker, home: npt.NDArray[np.float64]) -> None:
    """The sphere model's segment checks one call at a time (`CompiledSegments`), as the Python loop
    calls them (a query whose end the spheres wrongly reject plans there): once each, on a segment
    from ``home`` long enough for a batch in SIMD lanes. Compiled on first use, they took a query
    five CPU seconds."""
    away = home + np.eye(len(home))[0] * 0.5
    checker.segment_checked(home, away, 50, True, True)
    checker.free_prefix_checked(home, away, 0.5, 0.01, 10)


def _compile_shortcut_steps(checker: SphereCollisionChecker, home: npt.NDArray[np.float64]) -> None:
    """The shortcut's compiled steps (`compiled_shortcut.CompiledShortcutSteps`), each once on a
    short path through ``home``."""
    from kitchen_tamp.joint_spacing import PLANNING_RESOLUTION_RAD
    from kitchen_tamp.motion.sampling.compiled_shortcut import CompiledShortcutSteps
    from kitchen_tamp.motion.sampling.shortcut_settings import ShortcutHyperparameters

    path = home + np.outer([0.0, 0.01, 0.02], np.eye(len(home))[0])
    steps = CompiledShortcutSteps(checker.compiled_validity(), PLANNING_RESOLUTION_RAD)
    steps.connect_furthest(path)
    steps.random_tries(path, np.full((1, 2), 0.5), ShortcutHyperparameters(), math.inf)
    steps.cut_corners(steps.prune(path))


def _compile_planning_kernels(task: Task) -> None:
    from kitchen_tamp.planning.heuristics import RelaxedExploration
    from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
    from kitchen_tamp.planning.search.alternating_greedy import DEFAULT_BOOST
    from kitchen_tamp.planning.search.compiled_greedy import compiled_lazy_search
    from kitchen_tamp.planning.search.greedy_kernel_loading import jit_kernel
    from kitchen_tamp.planning.search.result import SearchBudget

    evaluator = LandmarkEvaluator(RelaxedExploration(task, "hadd"))
    evaluator.compiled_after_work = -1  # through the kernels from the first state
    evaluator.root()
    compiled_lazy_search(evaluator, True, DEFAULT_BOOST, SearchBudget(None, 1), jit_kernel())
    _compile_c_search()


def _compile_c_search() -> None:
    """The greedy search in C (``native_greedy``), or say why not (a long search then hands over to numba's
    JIT kernel, the same search)."""
    import subprocess

    from kitchen_tamp.planning.search.native_greedy import compile_library

    try:
        compile_library()
    except (OSError, subprocess.CalledProcessError) as error:  # no C compiler, or it failed
        detail = (error.stderr or error) if isinstance(error, subprocess.CalledProcessError) else error
        reason = " ".join(str(detail).split())
        print(f"not compiled: the greedy search in C ({type(error).__name__}: {reason}); "
              "long searches will hand over to numba's JIT kernel, the same search")


def main() -> int:
    clock = time.perf_counter()
    # numba decides where its cache goes when the kernels are imported: before the cache moves
    import kitchen_tamp.motion.geometry.spheres
    import kitchen_tamp.motion.geometry.spheres.kernels.ahead_of_time
    import kitchen_tamp.motion.geometry.spheres.kernels.clearance
    import kitchen_tamp.motion.geometry.spheres.kernels.segments
    import kitchen_tamp.motion.sampling.rrt_connect_kernel
    import kitchen_tamp.planning.relaxed_kernel
    import kitchen_tamp.planning.search.greedy_kernel  # noqa: F401

    saved = os.environ.get("XDG_CACHE_HOME")
    with tempfile.TemporaryDirectory(prefix="kitchen_tamp-prepare-") as cache:
        os.environ["XDG_CACHE_HOME"] = cache
        try:
            _compile_kernels()
        finally:
            if saved is None:
                os.environ.pop("XDG_CACHE_HOME", None)
            else:
                os.environ["XDG_CACHE_HOME"] = saved
    print(f"compiled the sphere model's and the planner's kernels in {time.perf_counter() - clock:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
