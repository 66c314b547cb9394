"""Compile the validity and clearance kernels ahead of time (numba's ``pycc``), at install.

`compile_ahead_of_time` takes the signatures numba's JIT gave
`valid_configurations_of_fields` (below), `clearance.clearance_penalties_of_arguments` and
`distance_grid.distance_grid_cells` for a real model's arrays (so each must have run once in this
process, as ``kitchen_tamp.cli.prepare`` makes them) and writes the extension module that
``loading.AHEAD_OF_TIME`` loads. Only ``kitchen_tamp.cli.prepare`` calls this.

A run must get the JIT kernels' answers to the bit: the clearance's last bits move trajectory
optimisation's iterates, so a run with the module would otherwise plan other paths than one
without. Two things make them so (``tests/motion/test_sphere_kernel_loading.py`` holds them to it):

- ``pycc`` compiles an exported function from its Python source with its own flags, not the ones
  its ``numba.njit`` gave it (``fastmath``), while the functions it calls keep theirs; so what is
  exported are wrappers without a body of their own (`valid_configurations_of_fields` here,
  `clearance.clearance_penalties_of_arguments`);
- ``pycc`` targets a generic processor by default, where the JIT compiles for this one, and the
  clearance's values then differed in their last bits (4.5e-12 on the kitchen): the module is
  compiled for this machine's processor (``target_cpu = "host"``), which is why its name carries
  the processor's signature as well as the sources' (``loading.AHEAD_OF_TIME``), so that an
  install shared by several machines never runs it on another processor.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numba
import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.kernels.clearance import clearance_penalties_of_arguments
from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid import distance_grid_cells
from kitchen_tamp.motion.geometry.spheres.kernels.loading import AHEAD_OF_TIME
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_rows
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import ValidityArrays, validity_scratch

FloatArray = npt.NDArray[np.float64]


@numba.njit(cache=True)
def valid_configurations_of_fields(
    fields: tuple[Any, ...],
    qs: FloatArray,
    margin: float,
    stop_at_invalid: bool,
) -> npt.NDArray[np.bool_]:
    """`validity.valid_configurations` with the arrays as the plain tuple `validity_fields.with_derived`
    gives (packed here, in compiled code): what the module exports, since an extension module cannot
    take a structref from Python."""
    arrays = ValidityArrays(*fields)  # type: ignore[no-untyped-call]
    return valid_rows(qs, arrays, margin, stop_at_invalid, validity_scratch(arrays, qs.shape[1]))


EXPORTED: dict[str, Any] = {
    "valid_configurations_of_fields": valid_configurations_of_fields,
    "distance_grid_cells": distance_grid_cells,
    "clearance_penalties_of_arguments": clearance_penalties_of_arguments,
}
"""The kernels the module exports, by the names `loading.sphere_kernels` reads."""


def compile_ahead_of_time() -> Path:
    """Compile the exported kernels with the signatures of their JIT runs (unless the module of these
    sources is there already); the module's folder."""
    return AHEAD_OF_TIME.compile(EXPORTED)
