"""Whole-process wall time: each planner started as a fresh process, as a user runs it.

For each problem and search, our ``pddl/activity_planning.py``, pyperplan's
command line and Fast Downward's driver are started in turn (alternating, so
that a slow spell of a loaded machine hits all three alike), ``rounds`` times;
the median wall time of each is reported with the plan length it printed.
Python's byte code caches and our Lark grammar cache are warm (one run before
timing), as they are for anyone past their first run. Children run without
``PYTHONDONTWRITEBYTECODE`` (set on the development machine, it would make every
run recompile our editable-installed modules while the installed peers load
theirs from byte code, which no user of an installed package pays).

Each run's CPU time (user + system, of the process and its children) is kept
beside its wall time: on a loaded machine the wall time of a short process is
mostly waiting for a core, and the CPU time is the steadier measure of the work.
The summary gives both, with the machine's load average before and after, and
the wall time of a bare ``python -c pass`` (the floor every Python planner pays).

Ours is timed twice per round: ``first``, the first run on these files (the
task cache emptied before each such run, so it parses, grounds and stores the
task), and ``repeat``, a run on unchanged files (served from the task cache,
see ``kitchen_tamp.planning.reading.task_cache``). Both are compared with pyperplan,
which has no cache and pays the same every run.

The verdict is the speed bar (``speed_bar_verdict``): pyperplan / ours at
least 5x in geometric mean and below 1 on no row, where a row on which both
take under 0.1 s counts as even (ratio 1) when we are within 30 ms of
pyperplan: below that, the interpreter's start-up decides, not the planner.
Rows pyperplan does not finish within the timeout are not counted; a row
pyperplan solves and we do not counts as slower.

Pairings (ours / pyperplan / Fast Downward):

- ``bfs``: breadth-first / ``-s bfs`` / ``astar(blind())``
- ``astar``: A* with h_max / ``-s astar -H hmax`` / ``astar(hmax())``
- ``gbfs``: GBFS with h_FF and alternating preferred queues / ``-s gbf -H hff`` (plain) /
  ``--alias lama-first`` (its best satisficing configuration: the gap to it, not a like-for-like)
"""

from __future__ import annotations

import importlib.util
import math
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ENTRY_SCRIPT = REPO / "pddl" / "activity_planning.py"
PROCESS_SEARCHES = ("bfs", "astar", "gbfs")

PYPERPLAN_ARGS = {"bfs": ["-s", "bfs"], "astar": ["-s", "astar", "-H", "hmax"],
                  "gbfs": ["-s", "gbf", "-H", "hff"]}
FAST_DOWNWARD_ARGS = {"bfs": ["--search", "astar(blind())"], "astar": ["--search", "astar(hmax())"],
                      "gbfs": ["--alias", "lama-first"]}


@dataclass
class ProcessRun:
    seconds: float | None  # median wall time of the runs that found a plan
    length: int | None
    note: str = ""
    cpu_seconds: float | None = None  # median CPU time (user + system) of the same runs


OURS = ("first", "ours")
"""Our two timings: the first run on new files (task cache miss) and a repeated run (hit)."""


def fast_downward_script() -> Path | None:
    # Located without importing: the wheel's Python wrapper needs unified-planning,
    # which we do not install; the driver script and binary are all we use.
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or not spec.submodule_search_locations:
        return None
    script = Path(next(iter(spec.submodule_search_locations))) / "downward" / "fast-downward.py"
    return script if script.exists() else None


def _environment(workdir: Path) -> dict[str, str]:
    env = {key: value for key, value in os.environ.items() if key != "PYTHONDONTWRITEBYTECODE"}
    # pyperplan's grounding iterates over sets: a fixed hash seed makes its rows reproducible.
    env.update(PYTHONHASHSEED="0", XDG_CACHE_HOME=str(workdir / "cache"))
    return env


def _task_cache(workdir: Path) -> Path:
    return workdir / "cache" / "kitchen_tamp" / "tasks"


def _command(planner: str, search: str, domain: Path, problem: Path, workdir: Path, fd_script: Path | None,
             timeout: float) -> list[str]:
    if planner in OURS:
        return [sys.executable, str(ENTRY_SCRIPT), str(problem), "--domain", str(domain), "--planner", search,
                "--timeout", str(timeout)]
    if planner == "pyperplan":
        return [sys.executable, "-m", "pyperplan", *PYPERPLAN_ARGS[search], str(domain), str(problem)]
    assert fd_script is not None
    alias, value = FAST_DOWNWARD_ARGS[search]
    head = [sys.executable, str(fd_script), "--plan-file", str(workdir / "fd.plan")]
    return [*head, alias, value, str(domain), str(problem)] if alias == "--alias" else [
        *head, str(domain), str(problem), alias, value]


def _plan_length(planner: str, completed: subprocess.CompletedProcess[str]) -> int | None:
    if planner in OURS:
        # The plain output a user reads (``--json`` would add importing json to every run).
        found = re.search(r"^length (\d+),", completed.stdout, re.MULTILINE)
        return int(found.group(1)) if completed.returncode == 0 and found else None
    text = completed.stdout + completed.stderr
    pattern = r"Plan length: (\d+)" if planner == "pyperplan" else r"Plan length: (\d+) step"
    match = re.search(pattern, text)
    return int(match.group(1)) if match else None


def _children_cpu_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run_once(command: list[str], planner: str, workdir: Path,
              timeout: float) -> tuple[float | None, float | None, int | None]:
    """Wall and CPU seconds of one run, and its plan length (seconds None without a plan)."""
    if planner == "first":
        shutil.rmtree(_task_cache(workdir), ignore_errors=True)
    cpu_start = _children_cpu_seconds()
    start = time.perf_counter()
    try:
        completed = subprocess.run(command, capture_output=True, text=True, cwd=workdir, timeout=timeout,
                                   env=_environment(workdir))
    except subprocess.TimeoutExpired:
        return None, None, None
    seconds = time.perf_counter() - start
    cpu_seconds = _children_cpu_seconds() - cpu_start
    length = _plan_length(planner, completed)
    if length is None:
        return None, None, None
    return seconds, cpu_seconds, length


def compare_processes(domain: Path, problem: Path, search: str, workdir: Path, fd_script: Path | None,
                      timeout: float, rounds: int) -> dict[str, ProcessRun]:
    """Median wall time per planner over ``rounds`` alternating fresh-process runs (fewer for slow rows)."""
    planners = [*OURS, "pyperplan"] + (["fd"] if fd_script else [])
    commands = {p: _command(p, search, domain, problem, workdir, fd_script, timeout) for p in planners}
    samples: dict[str, list[float]] = {p: [] for p in planners}
    cpu_samples: dict[str, list[float]] = {p: [] for p in planners}
    lengths: dict[str, int | None] = dict.fromkeys(planners)
    failed: set[str] = set()
    for round_index in range(rounds):
        for planner in planners:
            if planner in failed:
                continue
            seconds, cpu_seconds, length = _run_once(commands[planner], planner, workdir, timeout + 5)
            if seconds is None or cpu_seconds is None:
                failed.add(planner)
                continue
            samples[planner].append(seconds)
            cpu_samples[planner].append(cpu_seconds)
            lengths[planner] = length
        slowest = max((s[0] for s in samples.values() if s), default=0.0)
        if round_index == 0 and slowest > 5.0:
            break  # a slow row: one round is measurement enough, and keeps the run short
    runs = {}
    for planner in planners:
        if samples[planner]:
            runs[planner] = ProcessRun(statistics.median(samples[planner]), lengths[planner],
                                       cpu_seconds=statistics.median(cpu_samples[planner]))
        else:
            runs[planner] = ProcessRun(None, None, f"{planner}: no plan within {timeout:g} s")
    return runs


TINY_SECONDS = 0.1
"""A problem on which both planners finish within this is tiny: the interpreter's start-up decides it."""

EVEN_MARGIN_SECONDS = 0.030
"""On a tiny problem, a time within this of the peer's counts as even."""

REQUIRED_SPEED_UP = 5.0
"""The bar: at least this much faster than pyperplan in geometric mean, and slower on no problem."""


def geometric_mean(values: list[float]) -> float:
    return math.exp(sum(math.log(v) for v in values) / len(values))


def counted_ratio(ours: float, peer: float) -> float:
    """``peer / ours`` as the bar counts it: 1 (even) on a tiny problem where we are within the margin."""
    if ours < TINY_SECONDS and peer < TINY_SECONDS and abs(ours - peer) <= EVEN_MARGIN_SECONDS:
        return 1.0
    return peer / ours


def speed_bar_verdict(label: str, timings: list[tuple[str, float, float]], failed: list[str]) -> str:
    """One line: whether ``timings`` (row, ours, peer seconds; both solved) meet the bar.

    ``failed`` are the rows the peer solved and we did not, each a row we are slower on.
    """
    if not timings:
        return f"{label}: no row both solved"
    counted = [(row, counted_ratio(ours, peer)) for row, ours, peer in timings]
    mean = geometric_mean([ratio for _, ratio in counted])
    plain = geometric_mean([peer / ours for _, ours, peer in timings])
    worst_row, worst = min(counted, key=lambda item: item[1])
    slower = [row for row, ratio in counted if ratio < 1.0] + failed
    evens = sum(ratio == 1.0 for _, ratio in counted)
    passed = mean >= REQUIRED_SPEED_UP and not slower
    return (f"{label}: {'PASS' if passed else 'FAIL'}: geometric mean {mean:.2f}x as the bar counts "
            f"({evens} tiny rows even; {plain:.2f}x plain), worst {worst:.2f}x ({worst_row}) over "
            f"{len(counted)} rows both solved; slower on: {', '.join(slower) if slower else 'none'}")


def bare_python_seconds(workdir: Path, runs: int = 9) -> float:
    """Median wall time of ``python -c pass``: the start-up every Python planner pays first."""
    samples = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", "pass"], cwd=workdir, env=_environment(workdir), check=True)
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def _load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"


def process_table(rows: list[tuple[str, Path, Path, tuple[str, ...]]], workdir: Path, fd_script: Path | None,
                  timeout: float, rounds: int) -> None:
    """Print the whole-process table for (name, domain, problem, searches) rows, and a summary."""
    header = (f"{'problem':22} {'search':6} {'first s':>7} {'ours s':>7} {'pp s':>7} {'pp/1st':>6} "
              f"{'pp/ours':>7} {'cpu pp/1st':>10} {'cpu pp/ours':>11} {'FD s':>7} {'len ours/pp/FD':>15}")
    # One untimed run, so that byte code and our grammar cache are built (as after any first run).
    first_domain, first_problem = rows[0][1], rows[0][2]
    _run_once(_command("ours", "bfs", first_domain, first_problem, workdir, fd_script, timeout), "ours",
              workdir, timeout + 5)
    print(f"whole process, before: {_load()}; python -c pass {bare_python_seconds(workdir):.3f} s")
    print("median wall time of fresh processes, alternating "
          f"(up to {rounds} rounds; first = ours on new files, ours = repeated; cpu = the same ratios of "
          "CPU time; FD = lama-first for gbfs)")
    print(header)
    print("-" * len(header))
    timings: Timings = {(ours, clock): [] for ours in OURS for clock in ("wall", "cpu")}
    failed: list[str] = []
    for name, domain, problem, searches in rows:
        for search in searches:
            if search in PROCESS_SEARCHES:
                runs = compare_processes(domain, problem, search, workdir, fd_script, timeout, rounds)
                _record(f"{name} {search}", runs, timings, failed)
    print(f"\nwhole process, after: {_load()}")
    print(f"the bar: pyperplan / ours at least {REQUIRED_SPEED_UP:g}x in geometric mean and below 1 on no "
          f"row, a row where both take under {TINY_SECONDS:g} s counting as even when we are within "
          f"{EVEN_MARGIN_SECONDS * 1000:.0f} ms")
    for ours, label in (("first", "first run on new files"), ("ours", "repeated run")):
        for clock in ("wall", "cpu"):
            print(speed_bar_verdict(f"{label}, {clock} time", timings[ours, clock], failed))


Timings = dict[tuple[str, str], list[tuple[str, float, float]]]
"""(ours, clock) -> (row, our seconds, pyperplan's seconds) of the rows both solved."""


def _record(row: str, runs: dict[str, ProcessRun], timings: Timings, failed: list[str]) -> None:
    """Print one row of the table and keep its timings for the verdict."""
    peer, fd = runs["pyperplan"], runs.get("fd")
    shown = {}
    for ours in OURS:
        for clock, mine, theirs in (("wall", runs[ours].seconds, peer.seconds),
                                    ("cpu", runs[ours].cpu_seconds, peer.cpu_seconds)):
            if mine and theirs:
                timings[ours, clock].append((row, mine, theirs))
            shown[ours, clock] = f"{theirs / mine:.2f}" if mine and theirs else "-"
    lengths = "/".join("-" if r.length is None else str(r.length)
                       for planner, r in runs.items() if planner != "first")
    notes = " ".join(r.note for planner, r in runs.items() if r.note and planner != "first")
    optimal_lengths = {r.length for r in runs.values() if r.length is not None}
    if row.endswith((" bfs", " astar")) and len(optimal_lengths) > 1:
        notes += " LENGTHS DIFFER"
    if runs["ours"].seconds is None and peer.seconds is not None:
        failed.append(row)
    name, search = row.rsplit(" ", 1)
    print(f"{name:22} {search:6} {_fmt(runs['first'].seconds):>7} {_fmt(runs['ours'].seconds):>7} "
          f"{_fmt(peer.seconds):>7} {shown['first', 'wall']:>6} {shown['ours', 'wall']:>7} "
          f"{shown['first', 'cpu']:>10} {shown['ours', 'cpu']:>11} "
          f"{_fmt(fd.seconds if fd else None):>7} {lengths:>15} {notes}", flush=True)


def _fmt(value: float | None) -> str:
    return "-" if value is None else f"{value:.3f}"
