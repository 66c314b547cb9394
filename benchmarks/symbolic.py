"""Symbolic planning speed against pyperplan and Fast Downward: whole processes, then phases in-process.

First, what a user pays: each planner run as a fresh process per problem and
search (``symbolic_process``), on the kitchen, generated problems and real IPC
problems (``benchmarks/ipc/``), with the verdict of the speed bar. Then the
in-process comparison, which leaves out process start-up and imports: our run
(parse + translate + ground + search, the domain cache cleared first) against
pyperplan's (parse + ground + search) with the same search and heuristic, median
CPU seconds of several repeats, ratio pyperplan / ours; Fast Downward (the
``up-fast-downward`` wheel) once per row, CPU seconds of the child.

Pairings (ours / pyperplan / Fast Downward):

- ``bfs``: breadth-first / ``bfs`` / ``astar(blind())``
- ``astar``: A* with LM-cut / ``astar`` + ``lmcut`` / ``astar(lmcut())``
- ``ehc``: enforced hill climbing, h_FF, helpful actions first / ``ehs`` + ``hff``
  with preferred operators (pruning, no fallback) / ``ehc(h, preferred=[h])``
- ``gbfs``: greedy best-first, h_FF and the landmark count, lazy evaluation, alternating
  preferred/all (and novel) queues boosted on progress / ``gbf`` + ``hff`` with preferred operators
  (pruning) / ``lazy_greedy([h], preferred=[h], boost=1000)`` (the whole-process table: lama-first)
- ``ehc-plain``, ``gbfs-plain``: the same without helpful actions, against
  pyperplan's and Fast Downward's plain ``ehs``/``ehc(ff())`` and ``gbf``/``eager_greedy([ff()])``

A last table splits one run per problem into phases.

    python benchmarks/symbolic.py                  # everything (about 30 minutes)
    python benchmarks/symbolic.py --process-only   # the whole-process table and its verdict only
    python benchmarks/symbolic.py --quick          # small problems only
    python benchmarks/symbolic.py --process-only --ipc   # the IPC set against lama-first and pyperplan
    python benchmarks/symbolic.py --peers lama-first     # our gbfs against lama-first only, CPU seconds

``--peers lama-first`` (with ``--evaluations`` or ``--split``) is ``symbolic_lama``'s table of our
``gbfs`` against lama-first over the IPC set, whole processes in CPU seconds with the bar's verdict.
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from pddl_generators import blocks_world, gripper, ipc_problem, kitchen_problem, scaled_kitchen
from symbolic_process import fast_downward_script, geometric_mean, process_table, run_whole

from kitchen_tamp.planning import SEARCHES, SearchResult, Task, validate_plan
from kitchen_tamp.planning.grounding import ground
from kitchen_tamp.planning.loading import clear_domain_cache, domain_model, read_problem
from kitchen_tamp.planning.schemas import translate_problem
from kitchen_tamp.planning.search.best_first import greedy_best_first_search
from kitchen_tamp.planning.search.enforced_hill_climbing import enforced_hill_climbing

MAX_REPEATS = 21
"""Runs per row (median taken), fewer when one run is slow: see ``repeats``."""
REPEAT_SECONDS = 2.0


@dataclass(frozen=True)
class Pairing:
    pyperplan_search: str
    pyperplan_heuristic: str | None
    pyperplan_preferred: bool
    fast_downward: str


PAIRINGS: dict[str, Pairing] = {
    "bfs": Pairing("bfs", None, False, "astar(blind())"),
    "astar": Pairing("astar", "lmcut", False, "astar(lmcut())"),
    "ehc": Pairing("ehs", "hff", True, "let(h, ff(), ehc(h, preferred=[h]))"),
    "gbfs": Pairing("gbf", "hff", True, "let(h, ff(), lazy_greedy([h], preferred=[h], boost=1000))"),
    "ehc-plain": Pairing("ehs", "hff", False, "ehc(ff())"),
    "gbfs-plain": Pairing("gbf", "hff", False, "eager_greedy([ff()])"),
}

OUR_SEARCHES: dict[str, Callable[..., SearchResult]] = {
    **SEARCHES,
    "ehc-plain": partial(enforced_hill_climbing, helpful_actions=False),
    "gbfs-plain": partial(greedy_best_first_search, preferred_operators=False),
}
"""Each pairing's search of ours, called with the task and ``time_budget``."""


@dataclass
class Problem:
    name: str
    make: Callable[[], tuple[str, str]]
    searches: tuple[str, ...]


IPC_PROBLEMS: list[tuple[str, str, tuple[str, ...]]] = [
    ("transport", "task01.pddl", ("bfs", "astar", "gbfs")),
    ("transport", "task04.pddl", ("gbfs",)),
    ("transport", "task08.pddl", ("gbfs",)),
    ("elevators", "task01.pddl", ("gbfs",)),
    ("elevators", "task03.pddl", ("gbfs",)),
    ("elevators", "task28.pddl", ("gbfs",)),
    ("scanalyzer", "task01.pddl", ("bfs", "astar", "gbfs")),
    ("scanalyzer", "task08.pddl", ("gbfs",)),
    ("scanalyzer", "task13.pddl", ("gbfs",)),
    ("sokoban", "task01.pddl", ("bfs", "astar", "gbfs")),
    ("sokoban", "task08.pddl", ("gbfs",)),
    ("sokoban", "task23.pddl", ("gbfs",)),
    ("mystery", "instance-10.pddl", ("gbfs",)),
    ("mystery", "instance-19.pddl", ("gbfs",)),
    ("mystery", "instance-6.pddl", ("gbfs",)),
    ("woodworking", "task05.pddl", ("astar", "gbfs")),
    ("woodworking", "task20.pddl", ("gbfs",)),
    ("woodworking", "task30.pddl", ("gbfs",)),
    ("pegsol", "task13.pddl", ("gbfs",)),
    ("pegsol", "task23.pddl", ("gbfs",)),
    ("pegsol", "task28.pddl", ("gbfs",)),
    ("openstacks", "task08.pddl:domain08.pddl", ("gbfs",)),
    ("openstacks", "task18.pddl:domain18.pddl", ("gbfs",)),
    ("openstacks", "task28.pddl:domain28.pddl", ("gbfs",)),
    ("logistics", "task13.pddl", ("gbfs",)),
    ("logistics", "task23.pddl", ("gbfs",)),
    ("logistics", "task28.pddl", ("gbfs",)),
    ("depot", "task03.pddl", ("gbfs",)),
    ("depot", "task08.pddl", ("gbfs",)),
    ("depot", "task13.pddl", ("gbfs",)),
    ("rovers", "task08.pddl", ("gbfs",)),
    ("rovers", "task18.pddl", ("gbfs",)),
    ("rovers", "task23.pddl", ("gbfs",)),
    ("satellite", "task08.pddl", ("gbfs",)),
    ("satellite", "task13.pddl", ("gbfs",)),
    ("satellite", "task18.pddl", ("gbfs",)),
    ("freecell", "task03.pddl", ("gbfs",)),
    ("freecell", "task08.pddl", ("gbfs",)),
    ("freecell", "task13.pddl", ("gbfs",)),
    ("tpp", "task13.pddl", ("gbfs",)),
    ("tpp", "task18.pddl", ("gbfs",)),
    ("tpp", "task23.pddl", ("gbfs",)),
    ("zenotravel", "task08.pddl", ("astar", "gbfs")),
    ("zenotravel", "task13.pddl", ("gbfs",)),
    ("zenotravel", "task18.pddl", ("gbfs",)),
]
"""(domain folder, problem file[:domain file], searches): the real IPC set, 15 domains of three problems
each (``benchmarks/ipc/README.md``); blind search and A* where they finish."""


IPC_DOMAINS = {domain for domain, _, _ in IPC_PROBLEMS}


def problems(quick: bool) -> list[Problem]:
    every = ("bfs", "astar", "ehc", "gbfs", "ehc-plain", "gbfs-plain")
    guided = ("ehc", "gbfs")
    ipc = [Problem(f"{domain}-{file.split(':')[0].removesuffix('.pddl')}",
                   lambda domain=domain, file=file: ipc_problem(domain, *file.split(":")),  # type: ignore[misc]
                   searches)
           for domain, file, searches in IPC_PROBLEMS]
    items = [
        Problem("kitchen", lambda: kitchen_problem("problem.pddl"), every),
        Problem("kitchen-hard", lambda: kitchen_problem("problem_hard.pddl"), every),
        Problem("blocks-6", lambda: blocks_world(6, 1), every),
        Problem("gripper-6", lambda: gripper(6), every),
        Problem("kitchen-4b-5s-1d", lambda: scaled_kitchen(4, 5, 1, 0), every),
    ]
    if not quick:
        items += [
            Problem("blocks-8", lambda: blocks_world(8, 2), every),
            Problem("gripper-10", lambda: gripper(10), every),
            Problem("blocks-12", lambda: blocks_world(12, 3), (*guided, "gbfs-plain")),
            Problem("blocks-16", lambda: blocks_world(16, 4), guided),
            Problem("blocks-20", lambda: blocks_world(20, 5), guided),
            Problem("blocks-24", lambda: blocks_world(24, 6), guided),
            Problem("gripper-20", lambda: gripper(20), (*guided, "ehc-plain", "gbfs-plain")),
            Problem("gripper-40", lambda: gripper(40), guided),
            Problem("gripper-60", lambda: gripper(60), guided),
            Problem("kitchen-8b-10s-2d", lambda: scaled_kitchen(8, 10, 2, 1),
                    (*guided, "ehc-plain", "gbfs-plain")),
            Problem("kitchen-16b-20s-3d", lambda: scaled_kitchen(16, 20, 3, 2), guided),
        ]
    return items + (ipc[:2] if quick else ipc)


@dataclass
class Run:
    seconds: float | None
    length: int | None
    expanded: int | None
    note: str = ""
    phases: dict[str, float] = field(default_factory=dict)
    repeats: int = 0


def repeats(first_run_seconds: float) -> int:
    """How many more runs after the first: up to ``MAX_REPEATS`` in about ``REPEAT_SECONDS``."""
    if first_run_seconds <= 0:
        return MAX_REPEATS - 1
    return max(0, min(MAX_REPEATS - 1, int(REPEAT_SECONDS / first_run_seconds)))


def _median_phases(samples: list[dict[str, float]]) -> dict[str, float]:
    return {key: statistics.median(s[key] for s in samples) for key in samples[0]}


def run_ours_once(domain: Path, problem: Path, search: str,
                  timeout: float) -> tuple[dict[str, float], SearchResult, Task]:
    """One cold run (the domain cache cleared first), timed phase by phase in CPU seconds."""
    clear_domain_cache()
    clock = time.process_time
    start = clock()
    parsed_problem, source, _ = read_problem(problem)
    parsed = clock()
    model = domain_model(domain)
    modelled = clock()
    lifted = translate_problem(model, parsed_problem, source)
    translated = clock()
    task = ground(lifted)
    grounded = clock()
    result = OUR_SEARCHES[search](task, time_budget=timeout)
    searched = clock()
    phases = {"parse problem": parsed - start, "parse+check domain": modelled - parsed,
              "translate": translated - modelled, "ground": grounded - translated,
              "search": searched - grounded, "total": searched - start}
    return phases, result, task


def run_ours(domain: Path, problem: Path, search: str, timeout: float) -> Run:
    phases, result, task = run_ours_once(domain, problem, search, timeout)
    if result.plan is not None:
        assert validate_plan(task, result.plan).valid
    if not result.solved:
        return Run(None, None, result.expanded, f"ours: {result.status}", phases, 1)
    samples = [phases]
    for _ in range(repeats(phases["total"])):
        samples.append(run_ours_once(domain, problem, search, timeout)[0])
    median = _median_phases(samples)
    length = len(result.plan) if result.plan is not None else None
    return Run(median["total"], length, result.expanded, "", median, len(samples))


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
    """Run pyperplan (parse + ground + search) repeatedly; print median CPU times, plan length, expansions."""
    from pyperplan import planner as pyperplan

    pairing = PAIRINGS[search]
    counter = _ExpansionCounter()
    root = logging.getLogger()
    root.handlers = [counter]
    root.setLevel(logging.INFO)
    samples: list[dict[str, float]] = []
    solution: Any = None
    while not samples or len(samples) <= repeats(samples[0]["total"]):
        clock = time.process_time
        start = clock()
        parsed = pyperplan._parse(domain, problem)
        parsed_at = clock()
        task = pyperplan._ground(parsed)
        grounded_at = clock()
        heuristic: Any = (pyperplan.HEURISTICS[pairing.pyperplan_heuristic](task)
                          if pairing.pyperplan_heuristic else None)
        solution = pyperplan._search(task, pyperplan.SEARCHES[pairing.pyperplan_search], heuristic,
                                     use_preferred_ops=pairing.pyperplan_preferred)
        end = clock()
        samples.append({"parse": parsed_at - start, "ground": grounded_at - parsed_at,
                        "search": end - grounded_at, "total": end - start})
        if solution is None:
            break
    print(json.dumps({"phases": _median_phases(samples), "repeats": len(samples),
                      "length": None if solution is None else len(solution),
                      "expanded": counter.expanded}))


def run_pyperplan(domain: Path, problem: Path, search: str, timeout: float) -> Run:
    """pyperplan in a child process, so that a run without a time limit of its own can be cut off."""
    try:
        # pyperplan's grounding iterates over sets, so its operator order (and with
        # it the search) depends on the hash seed: fix it for reproducible rows.
        completed = subprocess.run(
            [sys.executable, __file__, "--pyperplan-worker", str(domain), str(problem), search],
            capture_output=True, text=True, timeout=timeout + 2 * REPEAT_SECONDS + 5,
            env={**os.environ, "PYTHONHASHSEED": "0"})
    except subprocess.TimeoutExpired:
        return Run(None, None, None, f"pyperplan >{timeout:g} s")
    if completed.returncode != 0:
        return Run(None, None, None, f"pyperplan exit {completed.returncode}")
    data = json.loads(completed.stdout.strip().splitlines()[-1])
    phases = data["phases"]
    if phases["total"] > timeout:
        return Run(None, None, None, f"pyperplan >{timeout:g} s")
    return Run(phases["total"] if data["length"] is not None else None, data["length"], data["expanded"],
               "" if data["length"] is not None else "pyperplan: no plan", phases, data["repeats"])


def run_fast_downward(script: Path, domain: Path, problem: Path, search: str, workdir: Path,
                      timeout: float) -> Run:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        completed = run_whole(
            [sys.executable, str(script), "--plan-file", str(workdir / "fd.plan"), str(domain),
             str(problem), "--search", PAIRINGS[search].fast_downward], timeout, cwd=workdir)
    except subprocess.TimeoutExpired:
        return Run(None, None, None, f"FD >{timeout:g} s")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    length = re.search(r"Plan length: (\d+) step", completed.stdout)
    expanded = re.findall(r"Expanded (\d+) state", completed.stdout)
    return Run(seconds, int(length.group(1)) if length else None,
               int(expanded[-1]) if expanded else None,
               "" if length else f"FD exit {completed.returncode}")


def _fmt(value: float | int | None, digits: int = 3) -> str:
    if value is None:
        return "-"
    return f"{value:.{digits}f}" if isinstance(value, float) else str(value)


def _ratio(ours: Run, peer: Run, timeout: float) -> str:
    if ours.seconds and peer.seconds:
        return f"{peer.seconds / ours.seconds:.1f}"
    if ours.seconds and peer.note.startswith("pyperplan >"):
        return f">{timeout / ours.seconds:.0f}"
    return "-"


def _phase_table(rows: list[tuple[str, Run, Run]]) -> None:
    print("\nphases of one run (median CPU ms; ours cold: domain parsed and checked every run)")
    header = (f"{'problem':20} {'search':10} {'parse dom+prob':>15} {'translate':>9} {'ground':>7} "
              f"{'search':>8} {'total':>8} | {'pp parse':>8} {'pp ground':>9} {'pp search':>9} "
              f"{'pp total':>8}")
    print(header)
    print("-" * len(header))
    for name, ours, peer in rows:
        o, p = ours.phases, peer.phases

        def ms(phases: dict[str, float], key: str) -> str:
            return f"{1000 * phases[key]:.2f}" if key in phases else "-"

        parse = (f"{1000 * o['parse+check domain']:.2f}+{1000 * o['parse problem']:.2f}"
                 if o else "-")
        print(f"{name:31} {parse:>15} {ms(o, 'translate'):>9} {ms(o, 'ground'):>7} "
              f"{ms(o, 'search'):>8} {ms(o, 'total'):>8} | {ms(p, 'parse'):>8} {ms(p, 'ground'):>9} "
              f"{ms(p, 'search'):>9} {ms(p, 'total'):>8}")


def _write_problem(item: Problem, folder: Path) -> tuple[Path, Path]:
    """Write a problem and its domain into ``folder``; their paths."""
    domain_text, problem_text = item.make()
    domain, problem = folder / f"{item.name}-domain.pddl", folder / f"{item.name}.pddl"
    domain.write_text(domain_text)
    problem.write_text(problem_text)
    return domain, problem


def in_process_table(selected: list[Problem], fd: Path | None, timeout: float) -> None:
    """Every search of every problem in-process, ours against pyperplan's (CPU time), then the phases."""
    header = (f"{'problem':20} {'search':10} {'ours s':>8} {'pp s':>8} {'ratio':>6} {'FD s':>7} "
              f"{'len ours/pp/FD':>15} {'expanded ours/pp/FD':>22}")
    print(f"\n{header}\n{'-' * len(header)}")
    timings: list[tuple[str, float, float]] = []
    phase_rows: list[tuple[str, Run, Run]] = []
    failed: list[str] = []  # rows pyperplan solved and we did not
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        # Warm up like an import: build the Lark parsers and run every search once.
        warm = Problem("warm", lambda: kitchen_problem("problem.pddl"), ())
        for search in OUR_SEARCHES:
            run_ours_once(*_write_problem(warm, workdir), search, timeout)
        for item in selected:
            domain, problem = _write_problem(item, workdir)
            for search in item.searches:
                ours = run_ours(domain, problem, search, timeout)
                peer = run_pyperplan(domain, problem, search, timeout)
                fd_run = run_fast_downward(fd, domain, problem, search, workdir, timeout) if fd else None
                if ours.seconds and peer.seconds:
                    timings.append((f"{item.name} {search}", ours.seconds, peer.seconds))
                elif ours.seconds is None and peer.seconds is not None:
                    failed.append(f"{item.name} {search}")
                runs = [r for r in (ours, peer, fd_run) if r is not None]
                print(f"{item.name:20} {search:10} {_fmt(ours.seconds):>8} {_fmt(peer.seconds):>8} "
                      f"{_ratio(ours, peer, timeout):>6} {_fmt(fd_run.seconds if fd_run else None):>7} "
                      f"{'/'.join(_fmt(r.length) for r in runs):>15} "
                      f"{'/'.join(_fmt(r.expanded) for r in runs):>22} "
                      f"{' '.join(r.note for r in runs if r.note)}", flush=True)
                if search == item.searches[0]:
                    phase_rows.append((f"{item.name:20} {search:10}", ours, peer))
    if timings:  # the bar is the whole-process table's; this one shows where the time goes
        ratios = [peer / ours for _, ours, peer in timings]
        slower = [row for row, ours, peer in timings if peer < ours] + failed
        print(f"\nin-process pyperplan / ours (median CPU time, parse + ground + search): geometric mean "
              f"{geometric_mean(ratios):.1f}x, minimum {min(ratios):.1f}x over {len(ratios)} rows both "
              f"solved; slower on: {', '.join(slower) if slower else 'none'}")
    _phase_table(phase_rows)


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small problems only")
    parser.add_argument("--no-fd", action="store_true", help="skip Fast Downward")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per planner run")
    parser.add_argument("--only", help="comma-separated problem names to run")
    parser.add_argument("--ipc", action="store_true", help="the IPC problems of benchmarks/ipc only")
    parser.add_argument("--process-only", action="store_true",
                        help="only the whole-process table (no in-process tables)")
    parser.add_argument("--rounds", type=int, default=None,
                        help="alternating fresh-process runs per row in the whole-process table "
                             "(default 5; 1 with --peers lama-first)")
    parser.add_argument("--peers", choices=("pyperplan-fd", "lama-first"), default="pyperplan-fd",
                        help="pyperplan and Fast Downward on every pairing (default), or lama-first against "
                             "our gbfs on the IPC set")
    parser.add_argument("--evaluations", action="store_true",
                        help="with --peers lama-first: CPU ms per evaluation, Python and compiled")
    parser.add_argument("--split", action="store_true",
                        help="with --peers lama-first: our fresh process's CPU seconds by phase")
    parser.add_argument("--further", type=Path, metavar="BENCHMARKS",
                        help="with --peers lama-first: the IPC set's domains' other problems from "
                             "BENCHMARKS, a folder laid out as pyperplan's benchmarks/ (DOMAIN/taskNN.pddl)")
    parser.add_argument("--tasks", type=int, nargs="+", default=[10, 15, 20, 25, 30],
                        help="with --further: the task numbers to take (default 10 15 20 25 30)")
    parser.add_argument("--pyperplan-worker", nargs=3, metavar=("DOMAIN", "PROBLEM", "SEARCH"),
                        help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.pyperplan_worker:
        pyperplan_worker(*args.pyperplan_worker)
        return 0
    if args.peers == "lama-first":
        from symbolic_lama import lama_first

        further = None if args.further is None else (args.further, args.tasks)
        return lama_first(args.only, args.rounds or 1, args.timeout, args.evaluations, args.split, further)
    logging.getLogger().setLevel(logging.WARNING)
    fd = None if args.no_fd else fast_downward_script()
    selected = [p for p in problems(args.quick) if (not args.only or p.name in args.only.split(","))
                and (not args.ipc or p.name.split("-")[0] in IPC_DOMAINS)]
    with tempfile.TemporaryDirectory() as tmp:
        rows = [(item.name, *_write_problem(item, Path(tmp)), item.searches) for item in selected]
        # One run first, so that byte code and our grammar cache are built (as after any first run).
        run_ours_once(rows[0][1], rows[0][2], "bfs", args.timeout)
        process_table(rows, Path(tmp), fd, args.timeout, args.rounds or 5)
    if not args.process_only:
        in_process_table(selected, fd, args.timeout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
