"""The activity planner's ``argparse`` parser: its ``--help``, and every command line the plain
reader of ``planner_arguments`` leaves to it (abbreviations, ``--option=value``, mistakes)."""

from __future__ import annotations

import argparse
import os
import sys

from kitchen_tamp.cli.planner_arguments import PLANNER_CHOICES


class _HelpFormatter(argparse.HelpFormatter):
    """argparse's help formatter, sized as ``shutil.get_terminal_size`` would, without importing ``shutil``.

    argparse builds a formatter at every ``add_argument``; the default one
    imports ``shutil`` (and with it bz2, lzma and zlib) for the width, a few
    milliseconds of every planner start. The rule is the same: ``$COLUMNS``,
    else the terminal's width, else 80; minus 2.
    """

    def __init__(self, prog: str, indent_increment: int = 2, max_help_position: int = 24,
                 width: int | None = None) -> None:
        super().__init__(prog, indent_increment, max_help_position,
                         width if width is not None else _terminal_columns() - 2)


def _terminal_columns() -> int:
    try:
        columns = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns  # type: ignore[union-attr]
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns if columns > 0 else 80


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="activity_planning.py", formatter_class=_HelpFormatter,
        description="Plan a PDDL problem with breadth-first search, enforced hill climbing "
                    "(h_FF), greedy best-first search (h_FF) or A* (h_max), and print the plans.")
    parser.add_argument("problem", nargs="?",
                        help="problem file; a bare name is looked up in the working directory, then in "
                             "the shipped kitchens (default: the kitchen problem.pddl)")
    parser.add_argument("--domain", help="domain file (default: domain.pddl beside the problem, else the "
                                         "shipped kitchen domain)")
    parser.add_argument("--planner", choices=PLANNER_CHOICES, action="append",
                        help="search to run; repeat for several (default: bfs and ehc)")
    parser.add_argument("--plan-out", metavar="FILE",
                        help="write the last requested planner's plan in IPC form")
    parser.add_argument("--json", action="store_true", help="print one JSON document")
    parser.add_argument("--timeout", type=float, metavar="S",
                        help="time budget in seconds for each planner")
    return parser
