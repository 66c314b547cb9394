"""The activity planner's command line, read without ``argparse`` when it is an ordinary one.

Importing ``argparse`` (with ``re``, ``gettext`` and ``locale``) is a few
milliseconds of a planner run that takes a few tens in all. So
``read_planner_arguments`` first reads the command line itself, accepting only
the exact option names, each value as the next word, and at most one problem;
anything else (``--help``, an abbreviation, ``--option=value``, a value that
starts with ``-``, an unknown planner, a timeout that is not a number, a second
problem) goes to the ``argparse`` parser of ``planner_parser``, which reads it
with its usual help and error messages. Where both read a command line they
agree (``tests/cli/test_planner_arguments.py`` compares them).
"""

from __future__ import annotations

from kitchen_tamp.planning.search.registry import SEARCHES

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from collections.abc import Sequence

PLANNER_CHOICES = (*SEARCHES, "all")
"""What ``--planner`` accepts."""


class PlannerArguments:
    """The options of one planner run, as ``argparse`` would set them (``None``: not given)."""

    def __init__(self, problem: str | None = None, domain: str | None = None,
                 planner: list[str] | None = None, plan_out: str | None = None, json: bool = False,
                 timeout: float | None = None) -> None:
        self.problem = problem
        self.domain = domain
        self.planner = planner
        self.plan_out = plan_out
        self.json = json
        self.timeout = timeout

    def __eq__(self, other: object) -> bool:
        return isinstance(other, PlannerArguments) and vars(self) == vars(other)


    def __repr__(self) -> str:
        return f"PlannerArguments({', '.join(f'{k}={v!r}' for k, v in vars(self).items())})"


def read_planner_arguments(argv: Sequence[str]) -> PlannerArguments:
    """The options on the command line ``argv``; exits 2 with argparse's message if they are wrong."""
    plain = read_plain_arguments(argv)
    if plain is not None:
        return plain
    from kitchen_tamp.cli.planner_parser import build_parser

    return PlannerArguments(**vars(build_parser().parse_args(argv)))


def read_plain_arguments(argv: Sequence[str]) -> PlannerArguments | None:
    """An ordinary command line's options, or ``None`` for one to leave to ``argparse``."""
    arguments = PlannerArguments()
    words = iter(argv)
    for word in words:
        if word == "--json":
            arguments.json = True
            continue
        if word in ("--domain", "--planner", "--plan-out", "--timeout"):
            value = next(words, "")
            if not value or value.startswith("-"):
                return None
            if word == "--domain":
                arguments.domain = value
            elif word == "--plan-out":
                arguments.plan_out = value
            elif word == "--planner":
                if value not in PLANNER_CHOICES:
                    return None
                arguments.planner = [*(arguments.planner or []), value]
            else:
                try:
                    arguments.timeout = float(value)
                except ValueError:
                    return None
            continue
        if not word or word.startswith("-") or arguments.problem is not None:
            return None
        arguments.problem = word
    return arguments
