"""Compile the greedy search kernel ahead of time (numba's ``pycc``), at install.

``compile_ahead_of_time`` takes the signature numba's JIT gave
``greedy_kernel.lazy_greedy_search`` for a real task's arrays (so the kernel
must have run once in this process) and writes the extension module that
``greedy_kernel_loading.ahead_of_time_kernel`` loads. Only
``kitchen_tamp.cli.prepare`` calls this.
"""

from __future__ import annotations

from pathlib import Path

from kitchen_tamp.planning.search import greedy_kernel
from kitchen_tamp.planning.search.greedy_kernel_loading import AHEAD_OF_TIME


def compile_ahead_of_time() -> Path:
    """Compile ``lazy_greedy_search`` with the signature of its JIT run (unless the module of these sources
    is there already); the module's folder."""
    return AHEAD_OF_TIME.compile({"lazy_greedy_search": greedy_kernel.lazy_greedy_search})
