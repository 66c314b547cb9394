"""Compile the validity and clearance kernels ahead of time (numba's ``pycc``), at install.

`compile_ahead_of_time` takes the signatures numba's JIT gave
`validity.valid_configurations_of_fields` and `clearance.clearance_penalties_of_arguments` for a real model's
arrays (so both must have run once in this process, as ``kitchen_tamp.cli.prepare`` makes them)
and writes the extension module that `loading.ahead_of_time_module` loads. Only
``kitchen_tamp.cli.prepare`` calls this.

A run must get the JIT kernels' answers to the bit: the clearance's last bits move trajectory
optimisation's iterates, so a run with the module would otherwise plan other paths than one
without. Two things make them so (``tests/motion/test_sphere_kernel_loading.py`` holds them to it):

- ``pycc`` compiles an exported function from its Python source with its own flags, not the ones
  its ``numba.njit`` gave it (``fastmath``), while the functions it calls keep theirs; so what is
  exported are wrappers without a body of their own (`validity.valid_configurations_of_fields`,
  `clearance.clearance_penalties_of_arguments`);
- ``pycc`` targets a generic processor by default, where the JIT compiles for this one, and the
  clearance's values then differed in their last bits (4.5e-12 on the kitchen): the module is
  compiled for this machine's processor (``target_cpu = "host"``), which is why its name carries
  the processor's signature as well as the sources' (`loading.ahead_of_time_name`), so that an
  install shared by several machines never runs it on another processor.
"""

from __future__ import annotations

import importlib.machinery
import warnings
from pathlib import Path
from typing import Any

from kitchen_tamp.motion.geometry.spheres.kernels.clearance import clearance_penalties_of_arguments
from kitchen_tamp.motion.geometry.spheres.kernels.loading import (
    MODULE_PREFIX,
    ahead_of_time_folder,
    ahead_of_time_name,
)
from kitchen_tamp.motion.geometry.spheres.kernels.validity import valid_configurations_of_fields

EXPORTED: dict[str, Any] = {
    "valid_configurations_of_fields": valid_configurations_of_fields,
    "clearance_penalties_of_arguments": clearance_penalties_of_arguments,
}
"""The kernels the module exports, by the names `loading.sphere_kernels` reads."""


def compile_ahead_of_time() -> Path:
    """Compile the exported kernels with the signatures of their JIT runs (unless the module of these
    sources is there already); the module's folder."""
    folder = ahead_of_time_folder()
    name = ahead_of_time_name()
    if any((folder / (name + suffix)).exists() for suffix in importlib.machinery.EXTENSION_SUFFIXES):
        return folder
    signatures = {}
    for export_name, kernel in EXPORTED.items():
        overloads = list(kernel.overloads.values())
        if len(overloads) != 1:
            raise RuntimeError(f"expected one compiled signature of {export_name}, found {len(overloads)}")
        signatures[export_name] = overloads[0].signature
    folder.mkdir(exist_ok=True)
    for stale in folder.glob(MODULE_PREFIX + "*"):  # compiled from earlier sources
        stale.unlink()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pycc's pending deprecation
        from numba.pycc import CC  # type: ignore[attr-defined]

        module = CC(name)  # type: ignore[no-untyped-call]
        module.output_dir = str(folder)
        module.verbose = False
        module.target_cpu = "host"
        for export_name, kernel in EXPORTED.items():
            module.export(export_name, signatures[export_name])(kernel.py_func)  # type: ignore[no-untyped-call]
        module.compile()
    return folder
