"""Compile the greedy search kernel ahead of time (numba's ``pycc``), at install.

``compile_ahead_of_time`` takes the signature numba's JIT gave
``greedy_kernel.lazy_greedy_search`` for a real task's arrays (so the kernel
must have run once in this process) and writes the extension module that
``greedy_kernel_loading.ahead_of_time_kernel`` loads. Only
``kitchen_tamp.cli.prepare`` calls this.
"""

from __future__ import annotations

import importlib.machinery
import warnings
from pathlib import Path

from kitchen_tamp.planning.search import greedy_kernel
from kitchen_tamp.planning.search.greedy_kernel_loading import ahead_of_time_folder, ahead_of_time_name


def compile_ahead_of_time() -> Path:
    """Compile ``lazy_greedy_search`` with the signature of its JIT run (unless the module of these sources
    is there already); the module's folder."""
    folder = ahead_of_time_folder()
    name = ahead_of_time_name()
    if any((folder / (name + suffix)).exists() for suffix in importlib.machinery.EXTENSION_SUFFIXES):
        return folder
    overloads = list(greedy_kernel.lazy_greedy_search.overloads.values())
    if len(overloads) != 1:
        raise RuntimeError(f"expected one compiled signature of the search kernel, found {len(overloads)}")
    folder.mkdir(exist_ok=True)
    for stale in folder.glob("greedy_search_*"):  # compiled from earlier sources
        stale.unlink()
    signature = overloads[0].signature  # type: ignore[attr-defined]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pycc's pending deprecation
        from numba.pycc import CC  # type: ignore[attr-defined]

        module = CC(name)  # type: ignore[no-untyped-call]
        module.output_dir = str(folder)
        module.verbose = False
        export = module.export("lazy_greedy_search", signature)  # type: ignore[no-untyped-call]
        export(greedy_kernel.lazy_greedy_search.py_func)
        module.compile()
    return folder
