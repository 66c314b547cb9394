"""Argument parsing and exit codes for the entry scripts (see DESIGN.md)."""

from enum import IntEnum


class ExitCode(IntEnum):
    """Exit codes shared by both command-line programs."""

    SOLVED = 0
    NO_PLAN = 1  # no plan exists, or refinement/search failed within its budget
    BAD_INPUT = 2  # usage, unreadable or malformed file, unwritable output, a setup that cannot run
    INTERNAL_ERROR = 3
    INTERRUPTED = 130  # Ctrl-C: 128 + SIGINT, as shells report it
