"""When the process began, and leaving it without the interpreter's tear-down.

A run's ``timing`` counts from the moment the process was started (before Python
loaded a module), so its phases add up to the time the user waited. When the
report is written and the verdict printed, nothing is left to do: `exit_now`
flushes the output and ends the process at once, skipping the tear-down of
Drake, numba and PyBullet's modules and objects (about a second on a loaded
machine), which no one waits for on purpose.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from typing import NoReturn


def seconds_since_start() -> float | None:
    """Seconds since this process was started, from ``/proc`` (10 ms resolution); None without it."""
    try:
        stat = Path("/proc/self/stat").read_text()
        start_ticks = int(stat[stat.rindex(")") + 2 :].split()[19])  # field 22: starttime
        uptime = float(Path("/proc/uptime").read_text().split()[0])
        return max(0.0, uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return None


def process_start() -> float:
    """The ``time.perf_counter()`` reading at which this process started (now, where unknown)."""
    now = time.perf_counter()
    return now - (seconds_since_start() or 0.0)


def exit_now(code: int) -> NoReturn:
    """Flush stdout and stderr and end the process with ``code``, skipping the interpreter's
    tear-down (files are written and closed by then; child processes are joined)."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
