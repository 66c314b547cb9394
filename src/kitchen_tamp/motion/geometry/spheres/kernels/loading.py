"""Where a run's validity and clearance kernels come from: the module compiled ahead of time, or
numba's JIT.

Importing numba and readying its compiler cost a run about 0.7 s of one core before its first
check (the import 0.3 s, numba's typing and target registries 0.35-0.4 s on the first call,
reading the cached kernels the rest), more than a kitchen run's motion planning. So ``make
install`` (``python -m kitchen_tamp.cli.prepare``) also compiles the kernels a kitchen run
calls, the validity of a batch (`ahead_of_time.valid_configurations_of_fields`), the smooth
clearance (`clearance.clearance_penalties_of_arguments`) and the filling of the obstacles'
distance grid the validity kernel reads (`distance_grid.distance_grid_cells`), ahead of time
with numba's ``pycc`` into an extension module in this package's ``__pycache__``
(`ahead_of_time`), named after a digest of the kernels' sources and of the processor it was
compiled for, so that an edited kernel is never served by a stale module, nor a module run on
another processor (``kitchen_tamp.ahead_of_time_modules``). Loading it needs numpy only
(under a millisecond). Without it (a read-only install, a kernel edited since the last ``make
install``) numba's JIT kernels serve, the same code.

The module takes the validity arrays as a plain tuple and packs them itself, which costs a call
about 5 microseconds more than the JIT kernel's structref (`validity_arrays`): fine for the
kitchen's few hundred batches, so the segment kernels and RRT-Connect's compiled loop, which
call it in their inner loops, keep to the JIT kernels.

This module imports neither numba nor the kernels' modules, which do.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.ahead_of_time_modules import AheadOfTimeModule
from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import with_derived

_HERE = Path(__file__).resolve().parent
AHEAD_OF_TIME = AheadOfTimeModule("sphere_kernels_", _HERE / "__pycache__", tuple(sorted(_HERE.glob("*.py"))),
                                  for_this_processor=True)
"""The kernels compiled ahead of time (`ahead_of_time`), every module of this package in the digest; for this
processor, since trajectory optimisation needs the clearance to equal the JIT kernel's to the bit (with
``pycc``'s generic processor it differed by up to 4.5e-12 on the kitchen)."""


PackedValidity = Any
"""The validity arrays as the serving kernel takes them: a plain tuple for the module compiled ahead of
time, a `validity_arrays.ValidityArrays` for the JIT kernel."""


@dataclass(frozen=True)
class SphereKernels:
    """The kernels serving this process, and whether they were compiled ahead of time."""

    pack: Callable[[tuple[Any, ...]], PackedValidity]
    """Arguments in ``VALIDITY_FIELDS`` order -> what ``valid`` takes."""
    valid: Callable[[npt.NDArray[np.float64], PackedValidity, float, bool], npt.NDArray[np.bool_]]
    """(qs, packed, margin, stop_at_invalid) -> per row, valid (`validity.valid_configurations`)."""
    clearance_penalties: Callable[..., tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]
    """(qs, the model's arrays as one tuple, floors, width) -> `clearance.clearance_penalties`."""
    ahead_of_time: bool


def ahead_of_time_kernels(module: ModuleType) -> SphereKernels:
    """The kernels of the module compiled ahead of time (``AHEAD_OF_TIME.load()``)."""
    fields_kernel = module.valid_configurations_of_fields

    def valid(qs: npt.NDArray[np.float64], packed: PackedValidity, margin: float,
              stop_at_invalid: bool) -> npt.NDArray[np.bool_]:
        answer: npt.NDArray[np.bool_] = fields_kernel(packed, qs, margin, stop_at_invalid)
        return answer

    def pack(arguments: tuple[Any, ...]) -> PackedValidity:
        return with_derived(arguments, module.distance_grid_cells)

    return SphereKernels(pack, valid, module.clearance_penalties_of_arguments, True)


def jit_kernels() -> SphereKernels:
    """numba's JIT kernels (importing numba, and compiling each kernel on its first call unless numba's
    cache holds it)."""
    from kitchen_tamp.motion.geometry.spheres.kernels.clearance import clearance_penalties_of_arguments
    from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_configurations
    from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import validity_arrays

    return SphereKernels(validity_arrays, valid_configurations, clearance_penalties_of_arguments, False)


_serving: list[SphereKernels] = []
"""The kernels serving this process once chosen (at most one)."""


def sphere_kernels() -> SphereKernels:
    """The kernels serving this process: the module compiled ahead of time when there is one for these
    sources, else the JIT kernels; chosen on the first call."""
    if not _serving:
        module = AHEAD_OF_TIME.load()
        _serving.append(jit_kernels() if module is None else ahead_of_time_kernels(module))
    return _serving[0]


def serve_jit_kernels() -> None:
    """Serve the checkers this process makes from now on with the JIT kernels, whatever is compiled ahead
    of time: what ``kitchen_tamp.cli.prepare`` does, so that it compiles them into numba's cache."""
    _serving[:] = [jit_kernels()]
