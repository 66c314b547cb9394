"""``pddl/activity_planning.py``: solve a PDDL problem with our searches and print the plans."""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.cli import CommandLineParser, ExitCode, exit_code_of
from kitchen_tamp.cli.output_paths import OutputPathError, check_output_file
from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.reading.task_cache import load_task_cached
from kitchen_tamp.planning.search.registry import SEARCH_DESCRIPTIONS, SEARCHES, plan
from kitchen_tamp.planning.search.result import SearchResult
from kitchen_tamp.planning.task import Task
from kitchen_tamp.planning.validation import plan_text, validate_plan
from kitchen_tamp.shipped_kitchens import DEFAULT_PROBLEM, domain_for, find_problem

DEFAULT_PLANNERS = ("bfs", "ehc")
PLANNER_CHOICES = (*SEARCHES, "all")
"""What ``--planner`` accepts: a search's name, or ``all`` of them."""


def _positive_seconds(text: str) -> float:
    """An argparse type: a time budget in seconds, a positive number."""
    try:
        seconds = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of seconds: {text!r}") from None
    if math.isnan(seconds) or seconds <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, got {text!r}")
    return seconds


def build_parser() -> argparse.ArgumentParser:
    parser = CommandLineParser(
        prog="activity_planning.py",
        description="Plan a PDDL problem with breadth-first search, enforced hill climbing "
                    "(h_FF), greedy best-first search (h_FF and landmarks) or A* (LM-cut), and print "
                    "the plans.")
    parser.add_argument("problem", nargs="?", default=DEFAULT_PROBLEM,
                        help="problem file; a bare name is looked up in the working directory, then in "
                             "the shipped kitchens (default: the kitchen problem.pddl)")
    parser.add_argument("--domain", type=Path,
                        help="domain file (default: domain.pddl beside the problem, else the "
                             "shipped kitchen domain)")
    parser.add_argument("--planner", choices=PLANNER_CHOICES, action="append",
                        help="search to run; repeat for several (default: bfs and ehc)")
    parser.add_argument("--plan-out", metavar="FILE", type=Path,
                        help="write the last requested planner's plan in IPC form")
    parser.add_argument("--json", action="store_true", help="print one JSON document")
    parser.add_argument("--timeout", type=_positive_seconds, metavar="S",
                        help="time budget in seconds for each planner")
    return parser


def _planners(requested: Sequence[str] | None) -> list[str]:
    """The searches to run, in the order asked, each once (``all`` expanded)."""
    names: list[str] = []
    for name in requested or DEFAULT_PLANNERS:
        for expanded in (SEARCHES if name == "all" else [name]):
            if expanded not in names:
                names.append(expanded)
    return names


def _result_json(result: SearchResult) -> dict[str, Any]:
    return {
        "planner": result.planner,
        "description": SEARCH_DESCRIPTIONS[result.planner],
        "status": result.status,
        "message": result.message,
        "plan": [action.text for action in result.plan] if result.plan is not None else None,
        "length": len(result.plan) if result.plan is not None else None,
        "expanded": result.expanded,
        "generated": result.generated,
        "evaluated": result.evaluated,
        "seconds": round(result.seconds, 6),
    }


def _print_task(task: Task, ground_seconds: float) -> None:
    print(f"problem {task.name} (domain {task.domain_name}): {len(task.objects)} objects, "
          f"{len(task.atoms)} atoms, {len(task.actions)} ground actions "
          f"(parsed and grounded in {ground_seconds:.3f} s)")
    print("--------------")


def _print_result(result: SearchResult) -> None:
    print(f"{result.planner.upper()} plan, {SEARCH_DESCRIPTIONS[result.planner]}:")
    if result.plan is None:
        print(f"  no plan: {result.message}")
    else:
        for number, action in enumerate(result.plan, start=1):
            print(f"{number}. {action}")
        if not result.plan:
            print("  (empty plan: the goal already holds)")
    length = "-" if result.plan is None else str(len(result.plan))
    print(f"length {length}, expanded {result.expanded} states, "
          f"evaluated {result.evaluated}, {result.seconds:.4f} s")
    print("--------------")


def _print_json(task: Task, ground_seconds: float, results: list[SearchResult]) -> None:
    import json  # only for --json

    print(json.dumps({
        "problem": task.name,
        "domain": task.domain_name,
        "objects": len(task.objects),
        "atoms": len(task.atoms),
        "actions": len(task.actions),
        "ground_seconds": round(ground_seconds, 6),
        "results": [_result_json(r) for r in results],
    }, indent=2))


def run(args: argparse.Namespace) -> int:
    """Plan ``args.problem`` with each requested search; every plan is validated before it is shown."""
    if args.plan_out is not None:
        check_output_file(args.plan_out, "--plan-out")
    started = time.perf_counter()
    problem = find_problem(args.problem)
    task = load_task_cached(problem, args.domain if args.domain is not None else domain_for(problem))
    ground_seconds = time.perf_counter() - started
    if not args.json:
        _print_task(task, ground_seconds)
    results: list[SearchResult] = []
    for name in _planners(args.planner):
        result = plan(task, name, time_budget=args.timeout)
        if result.plan is not None:
            check = validate_plan(task, result.plan)
            if not check.valid:
                raise AssertionError(f"{name} returned an invalid plan: {check.message}")
        results.append(result)
        if not args.json:
            _print_result(result)
    last = results[-1]
    if args.plan_out is not None and last.plan is not None:
        write_atomically(args.plan_out, plan_text(last.plan))
    if args.json:
        _print_json(task, ground_seconds, results)
    failed = [r for r in results if not r.solved]
    for result in failed:
        print(f"{result.planner}: {result.message}", file=sys.stderr)
    if args.plan_out is not None and last.plan is None:
        print(f"{args.plan_out}: not written, {last.planner} found no plan", file=sys.stderr)
    return int(ExitCode.NO_PLAN if failed else ExitCode.SOLVED)


BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "1")
"""The planner's numpy does no linear algebra, but numpy's OpenBLAS starts a thread per core when
numpy is imported (a search that hands over to the compiled kernel imports it), and those threads
spin waiting for work: 0.09-0.14 s of CPU on a run that hands over, nothing of its wall time
(docs/planner.md). So the planner's process keeps one, unless the user set the variable."""


def main(argv: Sequence[str] | None = None) -> int:
    """The planner's command line; a mistake in it exits 2 with one line (``SystemExit``)."""
    os.environ.setdefault(*BLAS_THREADS)  # before anything imports numpy
    args = build_parser().parse_args(argv)
    return exit_code_of(
        lambda: run(args),
        lambda error: str(error) if isinstance(error, (PlanningInputError, OutputPathError)) else None,
    )
