"""Argument parsing and exit codes for the entry scripts (see DESIGN.md)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from enum import IntEnum
from typing import NoReturn


class ExitCode(IntEnum):
    """Exit codes shared by both command-line programs."""

    SOLVED = 0
    NO_PLAN = 1  # no plan exists, or refinement/search failed within its budget
    BAD_INPUT = 2  # usage, unreadable or malformed file, unwritable output, a setup that cannot run
    INTERNAL_ERROR = 3
    INTERRUPTED = 130  # Ctrl-C: 128 + SIGINT, as shells report it


class CommandLineParser(argparse.ArgumentParser):
    """argparse, with a command-line mistake told in one line (exit 2) instead of usage and a line.

    The line is argparse's own message, which names the option (``argument
    --timeout: invalid float value: 'soon'``, ``unrecognized arguments: --fast``);
    the usage stays in ``--help``. Sub-command parsers are of this class too.
    """

    def error(self, message: str) -> NoReturn:
        self.exit(int(ExitCode.BAD_INPUT), f"error: {message} (see {self.prog} --help)\n")


def exit_code_of(body: Callable[[], int], bad_input_line: Callable[[Exception], str | None]) -> int:
    """Run a command's ``body`` and return its exit code, however it ends.

    ``bad_input_line(error)`` is the one line for an error in the user's input or
    setup (exit 2), ``None`` for a bug: that one gets its traceback and exit 3.
    Ctrl-C says ``interrupted`` and exits 130.
    """
    try:
        return body()
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return int(ExitCode.INTERRUPTED)
    except Exception as error:
        line = bad_input_line(error)
        if line is not None:
            print(f"error: {line}", file=sys.stderr)
            return int(ExitCode.BAD_INPUT)
        import traceback  # only for a bug

        traceback.print_exc()
        print(f"internal error: {type(error).__name__}: {error}", file=sys.stderr)
        return int(ExitCode.INTERNAL_ERROR)
