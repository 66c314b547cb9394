"""The planner's plain command-line reader agrees with its argparse parser wherever it reads a line."""

from __future__ import annotations

import contextlib
import io
import itertools

import pytest

from kitchen_tamp.cli.planner_arguments import PlannerArguments, read_plain_arguments, read_planner_arguments
from kitchen_tamp.cli.planner_parser import build_parser

WORDS = ("p.pddl", "q.pddl", "--domain", "d.pddl", "--planner", "bfs", "all", "dijkstra", "--plan-out",
         "--timeout", "2.5", "-1", "nan", "1e-9", "--json", "--dom", "--plan", "--domain=d.pddl", "-h",
         "--", "", "-")


def argparse_reading(argv: list[str]) -> PlannerArguments | None:
    """What argparse makes of ``argv``; None where it refuses it (or prints help) and exits."""
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            return PlannerArguments(**vars(build_parser().parse_args(argv)))
        except SystemExit:
            return None


def test_every_short_command_line_is_read_as_argparse_reads_it_or_left_to_argparse() -> None:
    read = 0
    for length in range(4):
        for words in itertools.product(WORDS, repeat=length):
            argv = list(words)
            plain = read_plain_arguments(argv)
            if plain is not None:
                assert repr(plain) == repr(argparse_reading(argv)), argv  # repr: nan == nan
                read += 1
    assert read > 500  # the plain reader does read the ordinary lines (541 of these)


@pytest.mark.parametrize("argv", [
    [],
    ["problem_hard.pddl"],
    ["problem.pddl", "--domain", "domain.pddl", "--planner", "bfs"],
    ["--planner", "gbfs", "task01.pddl", "--domain", "domain.pddl", "--timeout", "60"],
    ["--planner", "ehc", "--planner", "astar", "--plan-out", "out/kitchen.plan", "problem_hard.pddl"],
    ["--planner", "all", "--json"],
    ["--domain", "a.pddl", "--domain", "b.pddl", "p.pddl", "--timeout", "1", "--timeout", "2"],
])
def test_ordinary_command_lines_need_no_argparse(argv: list[str]) -> None:
    plain = read_plain_arguments(argv)
    assert plain is not None
    assert plain == argparse_reading(argv)


@pytest.mark.parametrize("argv", [
    ["--planner", "dijkstra"], ["--timeout", "soon"], ["a.pddl", "b.pddl"], ["--domain"], ["--plan", "x"],
])
def test_mistakes_get_argparse_s_message_and_exit_2(
        capsys: pytest.CaptureFixture[str], argv: list[str]) -> None:
    assert read_plain_arguments(argv) is None
    with pytest.raises(SystemExit) as exit_info:
        read_planner_arguments(argv)
    assert exit_info.value.code == 2
    assert capsys.readouterr().err.startswith("usage: activity_planning.py")


def test_abbreviations_and_equals_forms_are_read_by_argparse() -> None:
    argv = ["--dom", "d.pddl", "--planner=bfs", "--tim", "3", "p.pddl"]
    assert read_plain_arguments(argv) is None
    assert read_planner_arguments(argv) == PlannerArguments(
        problem="p.pddl", domain="d.pddl", planner=["bfs"], timeout=3.0)
