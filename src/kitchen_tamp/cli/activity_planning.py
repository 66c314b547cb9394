"""``pddl/activity_planning.py``: solve a PDDL problem with our searches and print the plans."""

from __future__ import annotations

import sys
import time

from kitchen_tamp.cli import ExitCode, exit_code_of
from kitchen_tamp.cli.output_paths import OutputPathError, check_output_file
from kitchen_tamp.cli.planner_arguments import PlannerArguments, read_planner_arguments
from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.reading.task_cache import load_task_cached
from kitchen_tamp.planning.search.registry import SEARCH_DESCRIPTIONS, SEARCHES, plan
from kitchen_tamp.planning.validation import plan_text, validate_plan

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from collections.abc import Sequence
    from typing import Any

    from kitchen_tamp.planning.search.result import SearchResult
    from kitchen_tamp.planning.task import Task

DEFAULT_PLANNERS = ("bfs", "ehc")


def _planners(requested: Sequence[str] | None) -> list[str]:
    if not requested:
        return list(DEFAULT_PLANNERS)
    names: list[str] = []
    for name in requested:
        for expanded in (SEARCHES if name == "all" else [name]):
            if expanded not in names:
                names.append(expanded)
    return names


def _result_json(task: Task, result: SearchResult) -> dict[str, Any]:
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


def _print_result(result: SearchResult) -> None:
    title = f"{result.planner.upper()} plan, {SEARCH_DESCRIPTIONS[result.planner]}:"
    print(title)
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


def run(args: PlannerArguments) -> int:
    plan_out = None
    if args.plan_out is not None:
        from pathlib import Path  # on use: the start-up of a run without --plan-out works on strings

        plan_out = Path(args.plan_out)
        check_output_file(plan_out, "--plan-out")
    started = time.perf_counter()
    from kitchen_tamp.shipped_kitchens import (  # start-up cost
        DEFAULT_PROBLEM,
        domain_file_for,
        find_problem_file,
    )

    problem = find_problem_file(args.problem or DEFAULT_PROBLEM)
    task = load_task_cached(problem, args.domain if args.domain else domain_file_for(problem))
    ground_seconds = time.perf_counter() - started
    if args.timeout is not None and args.timeout <= 0:
        raise PlanningInputError("--timeout must be a positive number of seconds")
    results: list[SearchResult] = []
    if not args.json:
        print(f"problem {task.name} (domain {task.domain_name}): {len(task.objects)} objects, "
              f"{len(task.atoms)} atoms, {len(task.actions)} ground actions "
              f"(parsed and grounded in {ground_seconds:.3f} s)")
        print("--------------")
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
    if plan_out is not None and last.plan is not None:
        from kitchen_tamp.atomic_files import write_atomically  # imported only when writing

        write_atomically(plan_out, plan_text(last.plan))
    if args.json:
        import json  # only for --json

        print(json.dumps({
            "problem": task.name,
            "domain": task.domain_name,
            "objects": len(task.objects),
            "atoms": len(task.atoms),
            "actions": len(task.actions),
            "ground_seconds": round(ground_seconds, 6),
            "results": [_result_json(task, r) for r in results],
        }, indent=2))
    failed = [r for r in results if not r.solved]
    for result in failed:
        print(f"{result.planner}: {result.message}", file=sys.stderr)
    if plan_out is not None and last.plan is None:
        print(f"{plan_out}: not written, {last.planner} found no plan", file=sys.stderr)
    return int(ExitCode.NO_PLAN if failed else ExitCode.SOLVED)


def main(argv: Sequence[str] | None = None) -> int:
    args = read_planner_arguments(sys.argv[1:] if argv is None else argv)
    return exit_code_of(
        lambda: run(args),
        lambda error: str(error) if isinstance(error, (PlanningInputError, OutputPathError)) else None,
    )
