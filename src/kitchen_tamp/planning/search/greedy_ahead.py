"""Compile the greedy search kernel ahead of time (numba's ``pycc``), at install.

``compile_ahead_of_time`` takes the signature numba's JIT gave
``greedy_kernel.lazy_greedy_search`` for a real task's arrays (so the kernel
must have run once in this process) and writes the extension module that
``greedy_kernel_loading.ahead_of_time_kernel`` loads. Only
``kitchen_tamp.cli.prepare`` calls this.
"""

from __future__ import annotations

import warnings
from pathlib import Path

from kitchen_tamp.planning.search import greedy_kernel
from kitchen_tamp.planning.search.greedy_kernel_loading import ahead_of_time_folder, ahead_of_time_name


def compile_ahead_of_time() -> Path:
    """Compile ``lazy_greedy_search`` with the signature of its JIT run; the module's folder."""
    overloads = list(greedy_kernel.lazy_greedy_search.overloads.values())
    if len(overloads) != 1:
        raise RuntimeError(f"expected one compiled signature of the search kernel, found {len(overloads)}")
    folder = ahead_of_time_folder()
    folder.mkdir(exist_ok=True)
    signature = overloads[0].signature  # type: ignore[attr-defined]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pycc's pending deprecation
        from numba.pycc import CC  # type: ignore[attr-defined]

        module = CC(ahead_of_time_name())  # type: ignore[no-untyped-call]
        module.output_dir = str(folder)
        module.verbose = False
        export = module.export("lazy_greedy_search", signature)  # type: ignore[no-untyped-call]
        export(greedy_kernel.lazy_greedy_search.py_func)
        module.compile()
    return folder
