"""The shortcut's steps in compiled calls (`shortcut_kernel`), for the sphere model.

`shortcut.shortcut_path` runs the same steps in the same order through either this or its Python
steps (`shortcut._PythonSteps`, any checker): joining the furthest waypoints in sight, random tries a
block of uniforms at a time (the clock read between blocks), pruning, cutting corners. One compiled
call a step, where the Python steps make a compiled segment check and a few numpy calls per try.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.sampling.shortcut import CORNER_CUT_FRACTIONS, MIN_IMPROVEMENT
from kitchen_tamp.motion.sampling.shortcut_kernel import (
    COUNTER_CHECKS,
    COUNTER_COUNT,
    COUNTER_SHORTCUTS,
    COUNTER_TRIES,
    COUNTER_UNSUCCESSFUL,
    corners_cut,
    furthest_vertex_jumps,
    pruned,
    random_tries,
    without_repeats,
)

if TYPE_CHECKING:
    from kitchen_tamp.motion.sampling.shortcut_settings import ShortcutHyperparameters

_JUMPS: Any = furthest_vertex_jumps
"""The compiled kernels, untyped for mypy (numba's dispatcher stubs take no argument list)."""
_TRIES: Any = random_tries
_PRUNED: Any = pruned
_CORNERS_CUT: Any = corners_cut
_WITHOUT_REPEATS: Any = without_repeats
_FRACTIONS = np.array(CORNER_CUT_FRACTIONS)
"""`shortcut.CORNER_CUT_FRACTIONS` as the corner-cutting kernel takes them."""


class CompiledShortcutSteps:
    """`shortcut._PythonSteps`' steps on the sphere model's compiled validity ``compiled`` (its
    `ValidityArrays` and margin), counted in one array the kernels add to."""

    def __init__(self, compiled: tuple[Any, float], resolution: float) -> None:
        self.arrays, self.margin = compiled
        self.resolution = resolution
        self.counters = np.zeros(COUNTER_COUNT, dtype=np.int64)

    @property
    def checks(self) -> int:
        return int(self.counters[COUNTER_CHECKS])

    @property
    def tries(self) -> int:
        return int(self.counters[COUNTER_TRIES])

    @property
    def shortcuts(self) -> int:
        return int(self.counters[COUNTER_SHORTCUTS])

    @property
    def unsuccessful(self) -> int:
        return int(self.counters[COUNTER_UNSUCCESSFUL])

    def connect_furthest(self, path: JointPath) -> JointPath:
        kept = _JUMPS(path, self.resolution, self.arrays, self.margin, self.counters)
        self.counters[COUNTER_SHORTCUTS] += int(np.count_nonzero(np.diff(kept) > 1))
        return np.asarray(path[kept], dtype=np.float64)

    def random_tries(
        self,
        path: JointPath,
        units: npt.NDArray[np.float64],
        params: ShortcutHyperparameters,
        deadline: float,
    ) -> JointPath:
        """A try per row of ``units`` until they run out or a limit is hit (the clock not read)."""
        patience = params.max_unsuccessful_tries or 0
        shorter: JointPath = _TRIES(
            path,
            units,
            params.max_iterations,
            patience,
            MIN_IMPROVEMENT,
            params.min_gain_per_length,
            self.resolution,
            self.arrays,
            self.margin,
            self.counters,
        )
        return shorter

    def prune(self, path: JointPath) -> JointPath:
        kept: JointPath = _PRUNED(path, self.resolution, self.arrays, self.margin, self.counters)
        return kept

    def cut_corners(self, path: JointPath) -> JointPath:
        cut = _CORNERS_CUT(path, _FRACTIONS, self.resolution, self.arrays, self.margin, self.counters)
        kept: JointPath = _WITHOUT_REPEATS(cut)
        return kept
