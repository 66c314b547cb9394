"""Symbolic planning speed against pyperplan and Fast Downward, in one process run.

For each problem and each search, our whole run (parse + ground + search) is
timed against pyperplan's (parse + ground + search) with the same search and
heuristic, both in this process and in CPU seconds; the ratio is
pyperplan / ours (above 1: we are faster). Fast Downward (the binary in the
``up-fast-downward`` wheel) runs as a subprocess on the same files with the
matching search, timed in CPU seconds of the child (translator included).

    python benchmarks/symbolic.py            # the full table
    python benchmarks/symbolic.py --quick    # small problems only
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import logging
import math
import re
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from pddl_generators import blocks_world, gripper, scaled_kitchen

from kitchen_tamp.planning import load_task, plan, validate_plan
from kitchen_tamp.planning.pddl_files import parse_domain

REPO = Path(__file__).resolve().parents[1]

# our search name -> (pyperplan search, pyperplan heuristic, Fast Downward search string)
PAIRINGS: dict[str, tuple[str, str | None, str]] = {
    "bfs": ("bfs", None, "astar(blind())"),
    "ehc": ("ehs", "hff", "ehc(ff())"),
    "gbfs": ("gbf", "hff", "eager_greedy([ff()])"),
    "astar": ("astar", "hmax", "astar(hmax())"),
}


@dataclass
class Problem:
    name: str
    make: Callable[[], tuple[str, str]]
    searches: tuple[str, ...]


def problems(quick: bool) -> list[Problem]:
    all_searches = ("bfs", "ehc", "gbfs", "astar")
    heuristic = ("ehc", "gbfs")
    items = [
        Problem("kitchen", lambda: _kitchen_files("problem.pddl"), all_searches),
        Problem("kitchen-hard", lambda: _kitchen_files("problem_hard.pddl"), all_searches),
        Problem("blocks-6", lambda: blocks_world(6, 1), all_searches),
        Problem("gripper-6", lambda: gripper(6), all_searches),
        Problem("kitchen-4b-5s-1d", lambda: scaled_kitchen(4, 5, 1, 0), all_searches),
    ]
    if not quick:
        items += [
            Problem("blocks-8", lambda: blocks_world(8, 2), ("bfs", "ehc", "gbfs", "astar")),
            Problem("blocks-12", lambda: blocks_world(12, 3), heuristic),
            Problem("blocks-16", lambda: blocks_world(16, 4), heuristic),
            Problem("blocks-20", lambda: blocks_world(20, 5), heuristic),
            Problem("blocks-24", lambda: blocks_world(24, 6), heuristic),
            Problem("gripper-10", lambda: gripper(10), ("bfs", "ehc", "gbfs", "astar")),
            Problem("gripper-20", lambda: gripper(20), heuristic),
            Problem("gripper-40", lambda: gripper(40), heuristic),
            Problem("gripper-60", lambda: gripper(60), heuristic),
            Problem("kitchen-8b-10s-2d", lambda: scaled_kitchen(8, 10, 2, 1), heuristic),
            Problem("kitchen-16b-20s-3d", lambda: scaled_kitchen(16, 20, 3, 2), heuristic),
        ]
    return items


def _kitchen_files(problem: str) -> tuple[str, str]:
    # The pyperplan parser has no negative preconditions, so every planner gets
    # the kitchen domain without open's (not (opened ?o)); the plans are the same.
    from pddl_generators import KITCHEN_STRIPS_DOMAIN

    return KITCHEN_STRIPS_DOMAIN, (REPO / "pddl" / problem).read_text()


@dataclass
class Run:
    seconds: float | None
    length: int | None
    expanded: int | None
    note: str = ""


def run_ours(domain: Path, problem: Path, search: str, timeout: float) -> Run:
    start = time.process_time()
    task = load_task(problem, domain)
    result = plan(task, search, time_budget=timeout)
    seconds = time.process_time() - start
    if result.plan is not None:
        assert validate_plan(task, result.plan).valid
    if not result.solved:
        return Run(None, None, result.expanded, f"ours: {result.status}")
    return Run(seconds, len(result.plan) if result.plan is not None else None, result.expanded)


class _ExpansionCounter(logging.Handler):
    pattern = re.compile(r"^(\d+) Nodes expanded")

    def __init__(self) -> None:
        super().__init__(logging.INFO)
        self.expanded: int | None = None

    def emit(self, record: logging.LogRecord) -> None:
        match = self.pattern.match(record.getMessage())
        if match:
            self.expanded = int(match.group(1))


def pyperplan_worker(domain: str, problem: str, search: str) -> None:
    """Run pyperplan (parse + ground + search) and print its CPU time, plan length and expansions."""
    from pyperplan import planner as pyperplan

    search_name, heuristic_name, _ = PAIRINGS[search]
    counter = _ExpansionCounter()
    root = logging.getLogger()
    root.handlers = [counter]
    root.setLevel(logging.INFO)
    start = time.process_time()
    parsed = pyperplan._parse(domain, problem)
    task = pyperplan._ground(parsed)
    heuristic: Any = pyperplan.HEURISTICS[heuristic_name](task) if heuristic_name else None
    solution = pyperplan._search(task, pyperplan.SEARCHES[search_name], heuristic)
    seconds = time.process_time() - start
    print(json.dumps({"seconds": seconds, "length": None if solution is None else len(solution),
                      "expanded": counter.expanded}))


def run_pyperplan(domain: Path, problem: Path, search: str, timeout: float) -> Run:
    """pyperplan in a child process, so that a run without a time limit of its own can be cut off."""
    try:
        completed = subprocess.run(
            [sys.executable, __file__, "--pyperplan-worker", str(domain), str(problem), search],
            capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return Run(None, None, None, f"pyperplan >{timeout:g} s")
    if completed.returncode != 0:
        return Run(None, None, None, f"pyperplan exit {completed.returncode}")
    data = json.loads(completed.stdout.strip().splitlines()[-1])
    return Run(data["seconds"], data["length"], data["expanded"],
               "" if data["length"] is not None else "pyperplan: no plan")


def fast_downward_script() -> Path | None:
    # Located without importing: the wheel's Python wrapper needs unified-planning,
    # which we do not install; the driver script and binary are all we use.
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or not spec.submodule_search_locations:
        return None
    script = Path(next(iter(spec.submodule_search_locations))) / "downward" / "fast-downward.py"
    return script if script.exists() else None


def run_fast_downward(script: Path, domain: Path, problem: Path, search: str, workdir: Path,
                      timeout: float) -> Run:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        completed = subprocess.run(
            [sys.executable, str(script), "--plan-file", str(workdir / "fd.plan"), str(domain),
             str(problem), "--search", PAIRINGS[search][2]],
            capture_output=True, text=True, cwd=workdir, timeout=timeout)
    except subprocess.TimeoutExpired:
        return Run(None, None, None, f"FD >{timeout:g} s")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    length = re.search(r"Plan length: (\d+) step", completed.stdout)
    expanded = re.findall(r"Expanded (\d+) state", completed.stdout)
    return Run(seconds, int(length.group(1)) if length else None,
               int(expanded[-1]) if expanded else None,
               "" if length else f"exit {completed.returncode}")


def _fmt(value: float | int | None, digits: int = 3) -> str:
    if value is None:
        return "-"
    return f"{value:.{digits}f}" if isinstance(value, float) else str(value)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small problems only")
    parser.add_argument("--no-fd", action="store_true", help="skip Fast Downward")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per planner run")
    parser.add_argument("--pyperplan-worker", nargs=3, metavar=("DOMAIN", "PROBLEM", "SEARCH"),
                        help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.pyperplan_worker:
        pyperplan_worker(*args.pyperplan_worker)
        return 0
    logging.getLogger().setLevel(logging.WARNING)
    # Warm up like an import: build the Lark parsers and run every code path once.
    parse_domain(REPO / "pddl" / "domain.pddl")
    for search in PAIRINGS:
        plan(load_task(REPO / "pddl" / "problem.pddl"), search)
    fd = None if args.no_fd else fast_downward_script()

    header = (f"{'problem':20} {'search':6} {'ours s':>8} {'pyperplan s':>11} {'ratio':>7} "
              f"{'FD s':>7} {'len ours/pp/FD':>15} {'expanded ours/pp/FD':>22}")
    print(header)
    print("-" * len(header))
    ratios: list[float] = []
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        for item in problems(args.quick):
            domain_text, problem_text = item.make()
            domain, problem = workdir / f"{item.name}-domain.pddl", workdir / f"{item.name}.pddl"
            domain.write_text(domain_text)
            problem.write_text(problem_text)
            for search in item.searches:
                ours = run_ours(domain, problem, search, args.timeout)
                peer = run_pyperplan(domain, problem, search, args.timeout)
                fd_run = (run_fast_downward(fd, domain, problem, search, workdir, args.timeout)
                          if fd else None)
                ratio = (peer.seconds / ours.seconds if ours.seconds and peer.seconds else None)
                if ratio is not None:
                    ratios.append(ratio)
                lengths = "/".join(_fmt(r.length) for r in (ours, peer, fd_run) if r is not None)
                expanded = "/".join(_fmt(r.expanded) for r in (ours, peer, fd_run) if r is not None)
                print(f"{item.name:20} {search:6} {_fmt(ours.seconds):>8} {_fmt(peer.seconds):>11} "
                      f"{_fmt(ratio, 1):>7} {_fmt(fd_run.seconds if fd_run else None):>7} "
                      f"{lengths:>15} {expanded:>22} "
                      f"{' '.join(n for n in (ours.note, peer.note, fd_run.note if fd_run else '') if n)}",
                      flush=True)
    if ratios:
        geometric = math.exp(sum(math.log(r) for r in ratios) / len(ratios))
        print(f"\nspeed-up over pyperplan (CPU time, parse + ground + search): geometric mean "
              f"{geometric:.1f}x, minimum {min(ratios):.1f}x over {len(ratios)} runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
