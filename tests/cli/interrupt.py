"""Run an entry script in a subprocess and press Ctrl-C (SIGINT) once it has printed a given line."""

from __future__ import annotations

import signal
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


@dataclass(frozen=True)
class Interrupted:
    """What the interrupted program printed and how it exited."""

    returncode: int
    stdout: str
    stderr: str


def interrupt_once_printed(
    script: str, args: list[str], line_prefix: str, timeout_s: float = 120.0
) -> Interrupted:
    """Run ``python -u REPO/script args``; send SIGINT right after a stdout line starting ``line_prefix``.

    Raises ``AssertionError`` if the program ends without printing such a line.
    """
    process = subprocess.Popen(
        [sys.executable, "-u", str(REPO / script), *args],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=REPO,
    )
    seen: list[str] = []
    try:
        assert process.stdout is not None
        for line in process.stdout:
            seen.append(line)
            if line.startswith(line_prefix):
                process.send_signal(signal.SIGINT)
                break
        else:
            process.wait(timeout_s)
            stderr = process.stderr.read() if process.stderr else ""
            raise AssertionError(f"{script} ended (exit {process.returncode}) before printing "
                                 f"{line_prefix!r}: {''.join(seen)}{stderr}")
        rest, stderr = process.communicate(timeout=timeout_s)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    return Interrupted(process.returncode, "".join(seen) + rest, stderr)
