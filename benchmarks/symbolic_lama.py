"""Our ``gbfs`` against Fast Downward's lama-first on the IPC set: ``symbolic.py --peers lama-first``.

    python benchmarks/symbolic.py --peers lama-first          # every IPC problem, one run each
    python benchmarks/symbolic.py --peers lama-first --rounds 3 --only depot-task03,sokoban-task23
    python benchmarks/symbolic.py --peers lama-first --evaluations  # CPU ms per evaluation
    python benchmarks/symbolic.py --peers lama-first --split  # our whole process's time by phase
    python benchmarks/symbolic.py --peers lama-first --further <pyperplan>/benchmarks --tasks 10 20 30

Each row runs ``pddl/activity_planning.py PROBLEM --domain DOMAIN --planner gbfs`` on new files (the task
cache emptied first) and ``fast-downward.py --alias lama-first DOMAIN PROBLEM`` as fresh processes,
alternating run by run (which goes first changes every round), and takes the median over ``--rounds``
(default 1) of each one's CPU time (user + system of the
process and its children, steadier than wall time on a shared machine). It prints the markdown table of
docs/planner.md's "Against lama-first on the IPC set" and the verdict against the bar: no row more than 2x
slower than lama-first, geometric mean at most 0.5x, every problem solved. ``benchmarks/symbolic.py
--process-only --ipc`` times the same rows as wall time with pyperplan beside them.

``--evaluations`` times instead, in this process, one ``LandmarkEvaluator`` evaluation (h_FF, helpful
actions, h_LM and its preferred operators) in Python and through the compiled kernels, in CPU milliseconds
on the states of seeded random walks (the initial state and up to 200 more), beside each row's
``work_per_evaluation``.

``--further BENCHMARKS`` runs the same table on the IPC set's domains' other problems (``--tasks``, by
number) from a folder laid out as pyperplan's ``benchmarks/`` (a clone of github.com/aibasel/pyperplan;
not on PyPI, so not fetched here): the bar holds for "any further IPC problems of the same domains" too.

``--split`` runs our planner once per row in a fresh process (new files) and splits its CPU seconds into
the interpreter's start, our imports, reading and grounding, and the search (with numpy and the compiled
search when the search hands over to it).

This module is the lama-first part of ``symbolic.py``, which parses the options and calls ``lama_first``.
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from pddl_generators import IPC_DIR
from symbolic import IPC_DOMAINS, IPC_PROBLEMS
from symbolic_process import (
    _command,
    _environment,
    _run_once,
    _task_cache,
    fast_downward_script,
    geometric_mean,
)

from kitchen_tamp.planning import load_task
from kitchen_tamp.planning.heuristics import RelaxedExploration
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.search.random_walks import random_walk_states

WORST_RATIO = 2.0
"""The bar: no row slower than this times lama-first's."""

MEAN_RATIO = 0.5
"""The bar: ours / lama-first at most this in geometric mean."""


def _measure_pair(commands: dict[str, list[str]], workdir: Path, timeout: float,
                  rounds: int) -> dict[str, tuple[float | None, int | None, int | None]]:
    """Per planner of ``commands`` (ours, lama-first): the median CPU seconds over ``rounds`` runs, plan
    length and expansions (None, None, None without a plan). The two take turns run by run, and which
    goes first changes every round: the first of two runs in a row is often the slower."""
    cpu: dict[str, list[float]] = {planner: [] for planner in commands}
    outcomes: dict[str, tuple[int | None, int | None]] = {}
    failed: set[str] = set()
    planners = list(commands)
    for round_number in range(rounds):
        for planner in planners if round_number % 2 == 0 else planners[::-1]:
            slow = bool(cpu[planner]) and cpu[planner][-1] > 5.0  # a slow row: one run is measurement enough
            if planner in failed or slow:
                continue
            _, cpu_seconds, outcome = _run_once(commands[planner], planner, workdir, timeout + 5)
            if cpu_seconds is None:
                failed.add(planner)
                continue
            cpu[planner].append(cpu_seconds)
            outcomes[planner] = (outcome.length, outcome.expanded)
    return {planner: (None, None, None) if planner in failed
            else (statistics.median(cpu[planner]), *outcomes[planner]) for planner in commands}


def _rows(only: set[str] | None) -> list[tuple[str, Path, Path]]:
    """The IPC rows with a gbfs pairing: name, domain file, problem file."""
    rows = []
    for domain_name, file, searches in IPC_PROBLEMS:
        row = f"{domain_name}-{file.split(':')[0].removesuffix('.pddl')}"
        if "gbfs" in searches and (only is None or row in only):
            problem_file, _, domain_file = file.partition(":")
            folder = IPC_DIR / domain_name
            rows.append((row, folder / (domain_file or "domain.pddl"), folder / problem_file))
    return rows


def further_rows(benchmarks: Path, numbers: list[int]) -> list[tuple[str, Path, Path]]:
    """Problems of the IPC set's domains that the set does not hold, numbered ``numbers``, from
    ``benchmarks`` laid out as pyperplan's collection (``DOMAIN/taskNN.pddl`` beside ``domain.pddl``,
    or openstacks' own ``domainNN.pddl``): the bar's "any further IPC problems of the same domains"."""
    held = {row for row, _, _ in _rows(None)}
    rows = []
    for domain_name in sorted(IPC_DOMAINS):
        folder = benchmarks / domain_name
        for number in numbers:
            row, problem = f"{domain_name}-task{number:02d}", folder / f"task{number:02d}.pddl"
            if row in held or not problem.exists():
                continue
            own_domain = folder / f"domain{number:02d}.pddl"
            rows.append((row, own_domain if own_domain.exists() else folder / "domain.pddl", problem))
    return rows


def evaluation_costs(domain: Path, problem: Path) -> tuple[str, float]:
    """The row's work per evaluation and CPU ms per evaluation in Python and through the kernels, and the
    CPU seconds of the first compiled evaluation (in the first row: loading numba and the kernels; numpy
    is loaded already)."""
    task = load_task(problem, domain)
    states = random_walk_states(task, seed=1, walks=10, length=20)
    milliseconds = []
    first = 0.0
    for after_work in (10**18, -1):
        evaluator = LandmarkEvaluator(RelaxedExploration(task, "hadd"))
        evaluator.compiled_after_work = after_work
        start = time.process_time()
        evaluator.root()
        first = time.process_time() - start
        start = time.process_time()
        for state in states:
            evaluator.evaluate(state, 0)
        milliseconds.append((time.process_time() - start) * 1000 / len(states))
    return f"{evaluator.work_per_evaluation} | {milliseconds[0]:.3f} | {milliseconds[1]:.3f}", first


SPLIT_SCRIPT = """
import sys, time
start = time.process_time()
import kitchen_tamp.cli.activity_planning
from kitchen_tamp.planning import load_task, plan
imported = time.process_time()
task = load_task(sys.argv[1], sys.argv[2])
grounded = time.process_time()
result = plan(task, "gbfs", time_budget=float(sys.argv[3]))
searched = time.process_time()
print(start, imported - start, grounded - imported, searched - grounded, result.expanded)
"""
"""Our planner's phases in one fresh process, in CPU seconds: the interpreter's start, our imports, reading
and grounding, the search (with numpy and the compiled search when it hands over)."""


def phase_split(domain: Path, problem: Path, workdir: Path, timeout: float) -> str:
    """One fresh process of ours, new files: its phases' CPU seconds and their sum (table cells)."""
    completed = subprocess.run([sys.executable, "-c", SPLIT_SCRIPT, str(problem), str(domain), str(timeout)],
                               capture_output=True, text=True, cwd=workdir, timeout=timeout + 5,
                               env=_environment(workdir), check=True)
    phases = [float(value) for value in completed.stdout.split()[:4]]
    return " | ".join(f"{value:.3f}" for value in [*phases, sum(phases)])


def _cell(value: float | int | None) -> str:
    return "-" if value is None else f"{value:.3f}" if isinstance(value, float) else str(value)


def lama_first(only_rows: str | None, rounds: int, timeout: float, evaluations: bool, split: bool,
               further: tuple[Path, list[int]] | None = None) -> int:
    """``symbolic.py --peers lama-first``: the table against lama-first, ``--evaluations`` or ``--split``;
    with ``further`` (a benchmarks folder and task numbers), on `further_rows` instead of the IPC set."""
    only = set(only_rows.split(",")) if only_rows else None
    selected = _rows(only) if further is None else [
        row for row in further_rows(*further) if only is None or row[0] in only]
    if evaluations:
        print("| problem | work per evaluation | Python ms | compiled ms |\n|---|---|---|---|")
        loading = None
        for row, domain, problem in selected:
            cells, first = evaluation_costs(domain, problem)
            loading = first if loading is None else loading
            print(f"| {row} | {cells} |", flush=True)
        print(f"\nthe first compiled evaluation (loading numba and the kernels): {loading:.3f} s CPU")
        return 0
    if split:
        print("| problem | interpreter s | imports s | read and ground s | search s | sum s |\n"
              "|---|---|---|---|---|---|")
        with tempfile.TemporaryDirectory(prefix="symbolic-lama-") as folder:
            for row, domain, problem in selected:
                shutil.rmtree(_task_cache(Path(folder)), ignore_errors=True)
                print(f"| {row} | {phase_split(domain, problem, Path(folder), timeout)} |", flush=True)
        return 0
    fd_script = fast_downward_script()
    if fd_script is None:
        print("Fast Downward (up_fast_downward) is not installed")
        return 1
    print("| problem | ours gbfs s | lama-first s | ours / lama-first | expanded ours / lama-first "
          "| length ours / lama-first |\n|---|---|---|---|---|---|")
    ratios: list[tuple[str, float]] = []
    unsolved: list[str] = []
    with tempfile.TemporaryDirectory(prefix="symbolic-lama-") as folder:
        workdir = Path(folder)
        for row, domain, problem in selected:
            commands = {planner: _command(planner, "gbfs", domain, problem, workdir, fd_script, timeout)
                        for planner in ("first", "fd")}
            runs = _measure_pair(commands, workdir, timeout, rounds)
            (ours, our_length, our_expanded), (fd, fd_length, fd_expanded) = runs["first"], runs["fd"]
            ratio = "-" if ours is None or fd is None else f"{ours / fd:.2f}"
            if ours is None:
                unsolved.append(row)
                ratio = f"unsolved in {timeout:g} s"
            elif fd is not None:
                ratios.append((row, ours / fd))
            print(f"| {row} | {_cell(ours)} | {_cell(fd)} | {ratio} "
                  f"| {_cell(our_expanded)}/{_cell(fd_expanded)} "
                  f"| {_cell(our_length)}/{_cell(fd_length)} |", flush=True)
    if not ratios:
        return 0
    mean = geometric_mean([r for _, r in ratios])
    over = [f"{row} {r:.1f}x" for row, r in sorted(ratios, key=lambda item: -item[1]) if r > WORST_RATIO]
    met = mean <= MEAN_RATIO and not over and not unsolved
    print(f"\nours / lama-first over {len(ratios)} rows: {mean:.2f}x in geometric mean (bar {MEAN_RATIO}x); "
          f"over {WORST_RATIO:g}x: {', '.join(over) or 'none'}; unsolved: {', '.join(unsolved) or 'none'}; "
          f"the bar is {'met' if met else 'not met'}")
    return 0
