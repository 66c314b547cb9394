"""Where the compiled greedy search comes from: the search in C, or numba's JIT kernel.

Importing numba costs about 0.7 s of CPU and reading the JIT kernels from its
cache some tenths more, which is more than many whole searches take. So
``make install`` (``python -m kitchen_tamp.cli.prepare``) compiles the search
in C (``greedy_search.c``) with the system's C compiler into a shared library
that ctypes loads in a few milliseconds, without numpy or numba
(``native_greedy``), named after a digest of its source so that an edited
search is never served by a stale build. Without it (no C compiler, a
read-only install, an edited ``greedy_search.c`` before the next
``make install``) a long search runs through numba's JIT kernel
(``greedy_kernel``), the same search.

This module imports neither numpy nor numba nor ctypes, and at load nothing beyond what the
planner imports anyway (every ``gbfs`` run loads it).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

SOLVED, UNSOLVABLE, OUT_OF_BUDGET = 0, 1, 2
"""The search's outcomes as the kernel returns them."""

NATIVE_HANDOVER_AFTER_SECONDS = 0.005
"""CPU seconds of the lazy greedy search in Python after which it hands over to the search in C
(``native_greedy``), when it is built: about what loading it and laying out a medium task's arrays cost
(4-7 ms with a few hundred actions, 25 ms with 19,000; docs/planner.md, "The search in C"). A clock, not
a count, decides, and that keeps runs deterministic: the C search takes the Python search's steps, so
the plan and the counts do not depend on when it takes over."""

GreedyKernel = Callable[..., Any]


def jit_kernel() -> GreedyKernel:
    """``lazy_greedy_search`` through numba's JIT (read from numba's cache after the first run)."""
    from kitchen_tamp.planning.search.greedy_kernel import lazy_greedy_search

    kernel: GreedyKernel = lazy_greedy_search
    return kernel


def native_library() -> Any:
    """The C search's library (``native_greedy.load_library``; a ``ctypes.CDLL``), None without one."""
    from kitchen_tamp.planning.search.native_greedy import load_library  # ctypes: only when handing over

    return load_library()
