"""Argument parsing and exit codes for the entry scripts (see DESIGN.md)."""

from __future__ import annotations

import sys

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from collections.abc import Callable


class ExitCode:
    """Exit codes shared by both command-line programs.

    Plain ints, not an ``IntEnum``: ``enum`` (with ``functools`` and ``collections``)
    would be a few milliseconds of every activity planner start.
    """

    SOLVED = 0
    NO_PLAN = 1  # no plan exists, or refinement/search failed within its budget
    BAD_INPUT = 2  # usage, unreadable or malformed file, unwritable output, a setup that cannot run
    INTERNAL_ERROR = 3
    INTERRUPTED = 130  # Ctrl-C: 128 + SIGINT, as shells report it


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
        import traceback  # only for a bug: traceback loads linecache and tokenize, ms of every start

        traceback.print_exc()
        print(f"internal error: {type(error).__name__}: {error}", file=sys.stderr)
        return int(ExitCode.INTERNAL_ERROR)
