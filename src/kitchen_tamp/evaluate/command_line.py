"""``python -m kitchen_tamp.evaluate``: a sweep of kitchen runs over problems x modes x seeds.

Exit codes: 0 every task ran (whatever its verdict), 2 the sweep cannot run (bad
arguments, a missing or malformed problem file, an unwritable output folder,
Ray unavailable), 130 interrupted (the rows written so far stay; ``--resume``).
"""

from __future__ import annotations

import argparse
import json
import shlex
import sys
from collections.abc import Sequence
from datetime import UTC, datetime
from pathlib import Path

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.cli import ExitCode
from kitchen_tamp.evaluate.grid import (
    MODES,
    GridError,
    TaskSpec,
    check_distinct_names,
    expand_grid,
    parse_seeds,
)
from kitchen_tamp.evaluate.local_pool import available_cores
from kitchen_tamp.evaluate.problem_sets import PROBLEM_SETS, problem_set
from kitchen_tamp.evaluate.random_problems import (
    RANDOM_PROBLEMS_DIR,
    RandomProblemError,
    generate_problems,
    write_manifest,
)
from kitchen_tamp.evaluate.ray_backend import RayUnavailableError
from kitchen_tamp.evaluate.results_table import RESULTS_FILE, ResultsTableError
from kitchen_tamp.evaluate.summary import write_summary
from kitchen_tamp.evaluate.sweep import RUNS_DIR, SweepPlan, run_sweep
from kitchen_tamp.evaluate.task_run import RunSettings, default_run_command
from kitchen_tamp.kitchen import KitchenError
from kitchen_tamp.kitchen.scene.choice import choose_scene
from kitchen_tamp.planning import PlanningInputError, load_task
from kitchen_tamp.shipped_kitchens import default_domain_path, domain_for, find_problem, kitchen_folder

DEFAULT_OUT = Path("out") / "evaluate"
DEFAULT_TIMEOUT_S = 600.0
SWEEP_LOG = "sweep.json"
"""Every command line that ran in the sweep folder, with its start time."""
INTERRUPTED_EXIT = 130


class SweepUsageError(Exception):
    """A sweep that cannot run as asked (exit 2)."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m kitchen_tamp.evaluate",
        description="Run final_project.py over problems x modes x seeds, each task in its own process, "
                    "on a local pool or on Ray; write results.csv, summary.md and plots.",
    )
    parser.add_argument("--problems", nargs="+", default=[], metavar="FILE",
                        help="problem files; bare names are also looked up in the shipped kitchens "
                             "(default: the default kitchen's problem*.pddl unless --random-problems "
                             "is given)")
    parser.add_argument("--problem-set", choices=PROBLEM_SETS,
                        help="also sweep a named set of shipped problems: 'benchmarks' is every problem "
                             "of the benchmark families (docs/tamp.md), each named after its family")
    parser.add_argument("--domain", type=Path,
                        help="domain file (default: domain.pddl beside each problem, else the shipped one)")
    parser.add_argument("--modes", nargs="+", choices=MODES, default=["rrt"], help="default: rrt")
    parser.add_argument("--seeds", default="0-19", help="seeds, e.g. 0-99 or 0-4,10 (default 0-19)")
    parser.add_argument("--random-problems", type=int, default=0, metavar="N",
                        help="also sweep N random kitchen problems, written to OUT/problems/")
    parser.add_argument("--problem-seed", type=int, default=0, metavar="S",
                        help="seed of the random problems")
    parser.add_argument("--random-modes", nargs="+", choices=MODES, metavar="MODE",
                        help="modes for the random problems (default: --modes)")
    parser.add_argument("--random-seeds", metavar="SEEDS",
                        help="seeds for the random problems (default: --seeds)")
    parser.add_argument("--workers", type=int, default=available_cores(),
                        help="tasks at once on this machine, or CPUs of a --ray local instance "
                             "(default: the cores, %(default)s)")
    parser.add_argument("--ray", metavar="ADDRESS|local",
                        help="run the tasks on Ray: 'local' starts an in-process instance, anything else is "
                             "the address of a running cluster (e.g. auto or ray://head:10001)")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="sweep folder (default %(default)s)")
    parser.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT_S, metavar="S",
                        help="seconds before a task is killed and recorded as a timeout "
                             "(default %(default)s)")
    parser.add_argument("--resume", action="store_true",
                        help="keep results.csv and run only the tasks it has no row for")
    parser.add_argument("--run-arg", action="append", default=[], metavar="ARG",
                        help="extra argument for every run, e.g. --run-arg=--max-samples=50 (repeatable)")
    parser.add_argument("--run-command", metavar="COMMAND",
                        help="command to run instead of 'python final_project.py' (MODE --problem P --seed S "
                             "--no-video --out DIR is appended)")
    return parser


def _problem_files(names: Sequence[str], domain: Path | None) -> list[Path]:
    problems = []
    for name in names:
        path = find_problem(name)
        if not path.is_file():
            raise SweepUsageError(f"problem file not found: {name}")
        # a malformed problem (or its domain's binding, or its scene) stops the sweep before it
        # starts; its domain and scene are found as a run finds them
        load_task(path, domain if domain is not None else domain_for(path))
        try:
            choose_scene(path, None, domain).kitchen_map()
        except KitchenError as error:
            raise SweepUsageError(str(error)) from None
        problems.append(path.resolve())
    return problems


def _check_out_dir(out: Path, resume: bool) -> None:
    try:
        out.mkdir(parents=True, exist_ok=True)
        write_atomically(out / ".writable", "")
        (out / ".writable").unlink()
    except OSError as error:
        raise SweepUsageError(f"cannot write to the sweep folder {out}: {error.strerror or error}") from None
    if (out / RESULTS_FILE).exists() and not resume:
        raise SweepUsageError(f"{out / RESULTS_FILE} exists: pass --resume to continue that sweep, "
                              "or choose another --out")


def _log_command(out: Path, argv: Sequence[str]) -> None:
    path = out / SWEEP_LOG
    try:
        log = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        log = []
    log.append({"started": datetime.now(UTC).isoformat(timespec="seconds"),
                "command": ["python", "-m", "kitchen_tamp.evaluate", *argv]})
    write_atomically(path, json.dumps(log, indent=2) + "\n")


def plan_sweep(args: argparse.Namespace, argv: Sequence[str]) -> SweepPlan:
    """Check the arguments, write the random problems, and lay out the tasks."""
    if args.workers < 1:
        raise SweepUsageError(f"--workers must be at least 1, got {args.workers}")
    if args.timeout <= 0:
        raise SweepUsageError(f"--timeout must be positive, got {args.timeout}")
    if args.random_problems < 0:
        raise SweepUsageError(f"--random-problems must be at least 0, got {args.random_problems}")
    if args.domain is not None and not args.domain.is_file():
        raise SweepUsageError(f"domain file not found: {args.domain}")
    names = args.problems
    if not names and not args.random_problems and not args.problem_set:
        names = sorted(str(path) for path in kitchen_folder().glob("problem*.pddl"))
    problems = _problem_files(names, args.domain)
    in_set = problem_set(args.problem_set) if args.problem_set else {}
    problems += _problem_files([str(path) for path in in_set], args.domain)
    seeds = parse_seeds(args.seeds)
    _check_out_dir(args.out, args.resume)
    tasks: list[TaskSpec] = expand_grid(problems, args.modes, seeds, in_set)
    if args.random_problems:
        domain = args.domain or default_domain_path()
        folder = args.out / RANDOM_PROBLEMS_DIR
        generated = generate_problems(args.random_problems, args.problem_seed, folder, domain)
        write_manifest(folder, generated)
        random_seeds = parse_seeds(args.random_seeds) if args.random_seeds else seeds
        random_paths = [problem.path.resolve() for problem in generated]
        tasks += expand_grid(random_paths, args.random_modes or args.modes, random_seeds)
        check_distinct_names([task.problem for task in tasks], in_set)
    command = tuple(shlex.split(args.run_command)) if args.run_command else default_run_command()
    extra = tuple(args.run_arg) + (("--domain", str(args.domain.resolve())) if args.domain else ())
    _log_command(args.out, argv)
    settings = RunSettings(command, args.timeout, (args.out / RUNS_DIR).resolve(), extra)
    return SweepPlan(tuple(tasks), args.out, settings, args.workers, args.ray, args.resume)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the sweep; the exit code (see the module's docstring)."""
    arguments = list(sys.argv[1:] if argv is None else argv)
    args = build_parser().parse_args(arguments)
    try:
        plan = plan_sweep(args, arguments)
        print(f"{len(plan.tasks)} tasks, {plan.workers} at a time "
              f"{'on Ray (' + plan.ray_address + ')' if plan.ray_address else 'on this machine'}; "
              f"results in {plan.out_dir / RESULTS_FILE}", file=sys.stderr, flush=True)
        rows = run_sweep(plan)
    except (SweepUsageError, GridError, PlanningInputError, RandomProblemError, RayUnavailableError,
            ResultsTableError) as error:
        print(f"error: {error}", file=sys.stderr)
        return int(ExitCode.BAD_INPUT)
    except KeyboardInterrupt:
        print(f"interrupted: the finished tasks are in {args.out / RESULTS_FILE}; rerun with --resume",
              file=sys.stderr)
        return INTERRUPTED_EXIT
    written = write_summary(args.out)
    solved = sum(row["status"] == "solved" for row in rows)
    print(f"{solved}/{len(rows)} tasks of this sweep solved; " + ", ".join(str(p) for p in written))
    return int(ExitCode.SOLVED)
