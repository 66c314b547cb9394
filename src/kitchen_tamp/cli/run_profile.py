"""``--profile``: a profile of the whole run (imports included), written beside its report.

The profiler starts before the entry script imports the package (the script
looks for ``--profile`` on its command line first), so start-up is in it too.
``profile.prof`` is cProfile's file (``python -m pstats``, snakeviz); ``profile.txt``
lists the functions that took longest, inclusive and by themselves. The child
process that draws replay.gif is not in it: its seconds are ``timing.gif_s``.
"""

from __future__ import annotations

import io
import marshal
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from kitchen_tamp.atomic_files import write_atomically

if TYPE_CHECKING:  # the profiler's modules load only when a profile is asked for
    import cProfile

PROFILE_OPTION = "--profile"
PROFILE_FILE = "profile.prof"
PROFILE_TEXT = "profile.txt"
LISTED_FUNCTIONS = 60
_running: list[cProfile.Profile] = []
"""The run's profiler, while it runs (at most one)."""


def profile_if_asked(argv: Sequence[str]) -> None:
    """Start profiling when ``--profile`` is among the arguments (unless it has started)."""
    if PROFILE_OPTION in argv and not _running:
        import cProfile

        profiler = cProfile.Profile()
        _running.append(profiler)
        profiler.enable()


def write_profile(folder: Path) -> Path | None:
    """Stop profiling and write ``profile.prof`` and ``profile.txt`` into ``folder`` (the run's
    folder); None when no profile was asked for."""
    if not _running:
        return None
    import pstats

    profiler = _running.pop()
    profiler.disable()
    text = io.StringIO()
    stats = pstats.Stats(profiler, stream=text)
    write_atomically(folder / PROFILE_FILE, marshal.dumps(stats.stats))  # type: ignore[attr-defined]
    text.write("Inclusive time (cumulative), longest first:\n")
    stats.sort_stats("cumulative").print_stats(LISTED_FUNCTIONS)
    text.write("\nTime in the function itself (tottime), longest first:\n")
    stats.sort_stats("tottime").print_stats(LISTED_FUNCTIONS)
    return write_atomically(folder / PROFILE_TEXT, text.getvalue())
