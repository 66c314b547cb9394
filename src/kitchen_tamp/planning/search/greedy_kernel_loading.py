"""Where the compiled greedy search comes from: C, a module compiled ahead of time, or numba's JIT.

Importing numba costs about 0.7 s of CPU and reading the JIT kernels from its
cache some tenths more, which is more than many whole searches take. So
``make install`` (``python -m kitchen_tamp.cli.prepare``) compiles the search
beforehand, twice: in C (``greedy_search.c``) into a shared library that
ctypes loads in a few milliseconds (``native_greedy``), and
``greedy_kernel.lazy_greedy_search`` with numba's ``pycc`` into an extension
module in this package's ``__pycache__`` (``greedy_ahead``), which needs
numpy's import (about 0.05 s). Each is named after a digest of its sources so
that an edited search is never served by a stale build
(``kitchen_tamp.ahead_of_time_modules``). A search hands over to the first of
them that is there; without either (no C compiler, a read-only install, an
edited kernel before the next ``make install``) it runs through numba's JIT
kernel, the same code.

This module imports neither numpy nor numba, and at load nothing beyond what the
planner imports anyway (every ``gbfs`` run loads it).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from kitchen_tamp.ahead_of_time_modules import AheadOfTimeModule

SOLVED, UNSOLVABLE, OUT_OF_BUDGET = 0, 1, 2
"""The search's outcomes as the kernel returns them."""

NATIVE_HANDOVER_AFTER_SECONDS = 0.005
"""CPU seconds of the lazy greedy search in Python after which it hands over to the C search
(``native_greedy``), when it is built: about what loading it and laying out a medium task's arrays cost
(4-5 ms for a few hundred actions, 25 ms for 19,000; docs/planner.md, "The search in C"). A clock, as
below: the C search takes the Python search's steps, so the plan and the counts do not depend on when."""

HANDOVER_AFTER_SECONDS = 0.15
"""CPU seconds of the lazy greedy search in Python after which it hands over to the kernel compiled ahead of
time: about what importing numpy and laying out the arrays cost (0.17-0.25 s, measured in docs/planner.md).
A clock, not a count, decides here, and that keeps runs deterministic: the kernel takes the Python search's
steps, so the plan and the counts do not depend on when the search hands over."""

STALL_SECONDS = 0.01
"""CPU seconds of the Python search without a new best h (since it started or last found one) after which
it hands over before ``HANDOVER_AFTER_SECONDS``: a search that stalls this early is likely to be long, and
a long one is some fifteen times faster in the kernel (docs/planner.md, "A stalled search hands over
early")."""

HANDOVER_COST_SECONDS = 0.08
"""What handing over costs in a fresh process, about: numpy's import and the arrays laid out (0.065-0.095 s
of CPU on a quiet machine, docs/planner.md). A search whose shortest likely run in Python (the root's
h_FF evaluations, each at the root's cost) costs more than this hands over at once: it would pay more in
Python than the hand-over and the kernel's own search together."""

_HERE = Path(__file__).resolve().parent
AHEAD_OF_TIME = AheadOfTimeModule("greedy_search_", _HERE / "__pycache__",
                                  (_HERE / "greedy_kernel.py", _HERE.parent / "relaxed_kernel.py"),
                                  for_this_processor=False)
"""The search compiled ahead of time (``greedy_ahead``) from its two sources, for any processor of this
family (it computes with integers only, so no result depends on how it is vectorised)."""

GreedyKernel = Callable[..., Any]


def ahead_of_time_kernel() -> GreedyKernel | None:
    """``lazy_greedy_search`` from the module compiled ahead of time; None without one for these sources."""
    module = AHEAD_OF_TIME.load()
    if module is None:
        return None
    kernel: GreedyKernel = module.lazy_greedy_search
    return kernel


def jit_kernel() -> GreedyKernel:
    """``lazy_greedy_search`` through numba's JIT (read from numba's cache after the first run)."""
    from kitchen_tamp.planning.search.greedy_kernel import lazy_greedy_search

    kernel: GreedyKernel = lazy_greedy_search
    return kernel


def native_library() -> Any:
    """The C search's library (``native_greedy.load_library``; a ``ctypes.CDLL``), None without one."""
    from kitchen_tamp.planning.search.native_greedy import load_library  # ctypes: only when handing over

    return load_library()
