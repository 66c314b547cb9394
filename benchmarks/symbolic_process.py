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
- ``astar``: A* with LM-cut / ``-s astar -H lmcut`` / ``astar(lmcut())`` (the plan lengths are
  compared: both are optimal)
- ``gbfs``: GBFS with h_FF and landmarks, alternating queues / ``-s gbf -H hff`` (plain) /
  ``--alias lama-first`` (Fast Downward's first plan of LAMA: the planner to beat)

Against lama-first there is a second verdict (``lama_verdict``), on the ``gbfs`` rows: ours at most
``MAX_LAMA_RATIO`` times lama-first's time on every row and at most ``MEAN_LAMA_RATIO`` in geometric
mean, whole process and (as a diagnosis) search alone, as each planner reports its search time.
"""

from __future__ import annotations

import importlib.util
import math
import os
import re
import resource
import shutil
import signal
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
ENTRY_SCRIPT = REPO / "pddl" / "activity_planning.py"
PROCESS_SEARCHES = ("bfs", "astar", "gbfs")

PYPERPLAN_ARGS = {"bfs": ["-s", "bfs"], "astar": ["-s", "astar", "-H", "lmcut"],
                  "gbfs": ["-s", "gbf", "-H", "hff"]}
FAST_DOWNWARD_ARGS = {"bfs": ["--search", "astar(blind())"], "astar": ["--search", "astar(lmcut())"],
                      "gbfs": ["--alias", "lama-first"]}


@dataclass
class ProcessRun:
    seconds: float | None  # median wall time of the runs that found a plan
    length: int | None
    note: str = ""
    cpu_seconds: float | None = None  # median CPU time (user + system) of the same runs
    expanded: int | None = None  # as the planner reports it
    search_seconds: float | None = None  # median of the search time the planner reports


@dataclass
class Outcome:
    """What one run printed: plan length, expansions and search seconds (None where it did not say)."""

    length: int | None
    expanded: int | None = None
    search_seconds: float | None = None


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


OUTPUT_PATTERNS = {
    # The plain output a user reads (``--json`` would add importing json to every run).
    "ours": (r"^length (\d+), expanded (\d+) states, evaluated \d+, (\d+(?:\.\d*)?(?:e-?\d+)?) s", 1, 2, 3),
    "pyperplan": (r"Plan length: (\d+)", 1, None, None),
    "fd": (r"Plan length: (\d+) step", 1, None, None),
}
"""Per planner: the pattern of its plan line and the groups holding length, expansions, search seconds."""


def _outcome(planner: str, completed: subprocess.CompletedProcess[str]) -> Outcome:
    key = "ours" if planner in OURS else planner
    text = completed.stdout if key == "ours" else completed.stdout + completed.stderr
    pattern, length_group, expanded_group, seconds_group = OUTPUT_PATTERNS[key]
    found = re.search(pattern, text, re.MULTILINE)
    if found is None or (key == "ours" and completed.returncode != 0):
        return Outcome(None)
    if key == "ours":
        return Outcome(int(found.group(length_group)), int(found.group(expanded_group or 0)),
                       float(found.group(seconds_group or 0)))
    expanded = re.findall(r"(\d+) Nodes expanded" if key == "pyperplan" else r"Expanded (\d+) state", text)
    seconds = re.findall(r"Search time: (\d+(?:\.\d*)?(?:e-?\d+)?)", text)
    return Outcome(int(found.group(length_group)), int(expanded[-1]) if expanded else None,
                   float(seconds[-1]) if seconds else None)


def _children_cpu_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_whole(command: list[str], timeout: float, **options: Any) -> subprocess.CompletedProcess[str]:
    """``subprocess.run`` with its output captured as text, the command in a session of its own whose
    every process is killed when the timeout expires or the benchmark is interrupted: Fast Downward's
    driver runs its search as a child, which killing the driver alone leaves running (for hours, with
    gigabytes of memory, on a problem it does not solve)."""
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          start_new_session=True, **options) as process:
        try:
            stdout, stderr = process.communicate(timeout=timeout)
        except BaseException:  # the timeout, or Ctrl-C: nothing of the run outlives it
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            raise
    return subprocess.CompletedProcess(command, process.returncode, stdout, stderr)


def _run_once(command: list[str], planner: str, workdir: Path,
              timeout: float) -> tuple[float | None, float | None, Outcome]:
    """Wall and CPU seconds of one run, and what it printed (seconds None without a plan)."""
    if planner == "first":
        shutil.rmtree(_task_cache(workdir), ignore_errors=True)
    cpu_start = _children_cpu_seconds()
    start = time.perf_counter()
    try:
        completed = run_whole(command, timeout, cwd=workdir, env=_environment(workdir))
    except subprocess.TimeoutExpired:
        return None, None, Outcome(None)
    seconds = time.perf_counter() - start
    cpu_seconds = _children_cpu_seconds() - cpu_start
    outcome = _outcome(planner, completed)
    if outcome.length is None:
        return None, None, outcome
    return seconds, cpu_seconds, outcome


def compare_processes(domain: Path, problem: Path, search: str, workdir: Path, fd_script: Path | None,
                      timeout: float, rounds: int) -> dict[str, ProcessRun]:
    """Median wall time per planner over ``rounds`` alternating fresh-process runs (fewer for slow rows)."""
    planners = [*OURS, "pyperplan"] + (["fd"] if fd_script else [])
    commands = {p: _command(p, search, domain, problem, workdir, fd_script, timeout) for p in planners}
    samples: dict[str, list[float]] = {p: [] for p in planners}
    cpu_samples: dict[str, list[float]] = {p: [] for p in planners}
    search_samples: dict[str, list[float]] = {p: [] for p in planners}
    outcomes: dict[str, Outcome] = {p: Outcome(None) for p in planners}
    failed: set[str] = set()
    for round_index in range(rounds):
        for planner in planners:
            if planner in failed:
                continue
            seconds, cpu_seconds, outcome = _run_once(commands[planner], planner, workdir, timeout + 5)
            if seconds is None or cpu_seconds is None:
                failed.add(planner)
                continue
            samples[planner].append(seconds)
            cpu_samples[planner].append(cpu_seconds)
            if outcome.search_seconds is not None:
                search_samples[planner].append(outcome.search_seconds)
            outcomes[planner] = outcome
        slowest = max((s[0] for s in samples.values() if s), default=0.0)
        if round_index == 0 and slowest > 5.0:
            break  # a slow row: one round is measurement enough, and keeps the run short
    runs = {}
    for planner in planners:
        if samples[planner]:
            searched = search_samples[planner]
            runs[planner] = ProcessRun(statistics.median(samples[planner]), outcomes[planner].length,
                                       cpu_seconds=statistics.median(cpu_samples[planner]),
                                       expanded=outcomes[planner].expanded,
                                       search_seconds=statistics.median(searched) if searched else None)
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


MAX_LAMA_RATIO = 2.0
"""The bar against lama-first: ours at most this many times its time on every ``gbfs`` row..."""

MEAN_LAMA_RATIO = 0.5
"""... and at most this in geometric mean."""


def lama_verdict(label: str, timings: list[tuple[str, float, float]], failed: list[str]) -> str:
    """One line: ours / lama-first over ``timings`` (row, our seconds, lama-first's), the worst row, the bar.

    ``failed`` are the rows lama-first solved and we did not.
    """
    if not timings:
        return f"{label}: no row both solved"
    ratios = [(row, ours / fd) for row, ours, fd in timings]
    mean = geometric_mean([ratio for _, ratio in ratios])
    worst_row, worst = max(ratios, key=lambda item: item[1])
    over = [f"{row} ({ratio:.2f}x)" for row, ratio in ratios if ratio > MAX_LAMA_RATIO] + failed
    passed = mean <= MEAN_LAMA_RATIO and not over
    return (f"{label}: {'PASS' if passed else 'FAIL'}: ours / lama-first {mean:.2f}x in geometric mean, "
            f"worst {worst:.2f}x ({worst_row}) over {len(ratios)} rows both solved; over "
            f"{MAX_LAMA_RATIO:g}x or unsolved: {', '.join(over) if over else 'none'}")


@dataclass
class Tally:
    """The timings the verdicts are computed from, kept as the rows are printed."""

    pyperplan: dict[tuple[str, str], list[tuple[str, float, float]]]  # (ours, clock) -> rows
    lama: dict[tuple[str, str], list[tuple[str, float, float]]]  # (ours, clock) -> gbfs rows
    failed: list[str]  # rows pyperplan solved and we did not
    lama_failed: list[str]  # gbfs rows lama-first solved and we did not
    worst: tuple[float, str] = (0.0, "")  # the gbfs row with the largest ours / lama-first (repeated, wall)


def process_table(rows: list[tuple[str, Path, Path, tuple[str, ...]]], workdir: Path, fd_script: Path | None,
                  timeout: float, rounds: int) -> None:
    """Print the whole-process table for (name, domain, problem, searches) rows, and a summary."""
    header = (f"{'problem':22} {'search':6} {'first s':>7} {'ours s':>7} {'pp s':>7} {'pp/1st':>6} "
              f"{'pp/ours':>7} {'cpu pp/1st':>10} {'cpu pp/ours':>11} {'FD s':>7} {'ours/FD':>7} "
              f"{'search ours/FD s':>16} {'expanded ours/pp/FD':>20} {'len ours/pp/FD':>15}")
    # One untimed run, so that byte code and our grammar cache are built (as after any first run).
    first_domain, first_problem = rows[0][1], rows[0][2]
    _run_once(_command("ours", "bfs", first_domain, first_problem, workdir, fd_script, timeout), "ours",
              workdir, timeout + 5)
    print(f"whole process, before: {_load()}; python -c pass {bare_python_seconds(workdir):.3f} s")
    print("median wall time of fresh processes, alternating "
          f"(up to {rounds} rounds; first = ours on new files, ours = repeated; cpu = the same ratios of "
          "CPU time; FD = lama-first for gbfs, astar(lmcut()) for astar; search = as each reports it)")
    print(header)
    print("-" * len(header))
    clocks = [(ours, clock) for ours in OURS for clock in ("wall", "cpu")]
    tally = Tally({key: [] for key in clocks}, {key: [] for key in [*clocks, ("ours", "search")]}, [], [])
    for name, domain, problem, searches in rows:
        for search in searches:
            if search in PROCESS_SEARCHES:
                runs = compare_processes(domain, problem, search, workdir, fd_script, timeout, rounds)
                _record(f"{name} {search}", runs, tally)
    print(f"\nwhole process, after: {_load()}")
    print(f"the bar: pyperplan / ours at least {REQUIRED_SPEED_UP:g}x in geometric mean and below 1 on no "
          f"row, a row where both take under {TINY_SECONDS:g} s counting as even when we are within "
          f"{EVEN_MARGIN_SECONDS * 1000:.0f} ms")
    for ours, label in (("first", "first run on new files"), ("ours", "repeated run")):
        for clock in ("wall", "cpu"):
            print(speed_bar_verdict(f"{label}, {clock} time", tally.pyperplan[ours, clock], tally.failed))
    if fd_script is None:
        return
    print(f"the bar against lama-first (gbfs rows): ours / lama-first at most {MAX_LAMA_RATIO:g}x on every "
          f"row and at most {MEAN_LAMA_RATIO:g}x in geometric mean")
    for ours, label in (("first", "first run on new files"), ("ours", "repeated run")):
        for clock in ("wall", "cpu"):
            print(lama_verdict(f"{label}, {clock} time", tally.lama[ours, clock], tally.lama_failed))
    print(lama_verdict("search alone, as each reports it", tally.lama["ours", "search"], tally.lama_failed))
    if tally.worst[1]:
        print(f"worst row against lama-first (repeated run, wall time):\n{tally.worst[1]}")


def _record(row: str, runs: dict[str, ProcessRun], tally: Tally) -> None:
    """Print one row of the table and keep its timings for the verdicts."""
    peer, fd = runs["pyperplan"], runs.get("fd")
    shown = {}
    for ours in OURS:
        for clock, mine, theirs in (("wall", runs[ours].seconds, peer.seconds),
                                    ("cpu", runs[ours].cpu_seconds, peer.cpu_seconds)):
            if mine and theirs:
                tally.pyperplan[ours, clock].append((row, mine, theirs))
            shown[ours, clock] = f"{theirs / mine:.2f}" if mine and theirs else "-"
    lengths = "/".join("-" if r.length is None else str(r.length)
                       for planner, r in runs.items() if planner != "first")
    expanded = "/".join("-" if r.expanded is None else str(r.expanded)
                        for planner, r in runs.items() if planner != "first")
    notes = " ".join(r.note for planner, r in runs.items() if r.note and planner != "first")
    optimal_lengths = {r.length for r in runs.values() if r.length is not None}
    if row.endswith((" bfs", " astar")) and len(optimal_lengths) > 1:
        notes += " LENGTHS DIFFER"
    if runs["ours"].seconds is None and peer.seconds is not None:
        tally.failed.append(row)
    name, search = row.rsplit(" ", 1)
    ratio = _record_lama(row, runs, fd, tally) if fd is not None and search == "gbfs" else None
    against_fd = "-" if ratio is None else f"{ratio:.2f}"
    searched = f"{_fmt(runs['ours'].search_seconds)}/{_fmt(fd.search_seconds if fd else None)}"
    line = (f"{name:22} {search:6} {_fmt(runs['first'].seconds):>7} {_fmt(runs['ours'].seconds):>7} "
            f"{_fmt(peer.seconds):>7} {shown['first', 'wall']:>6} {shown['ours', 'wall']:>7} "
            f"{shown['first', 'cpu']:>10} {shown['ours', 'cpu']:>11} "
            f"{_fmt(fd.seconds if fd else None):>7} {against_fd:>7} {searched:>16} {expanded:>20} "
            f"{lengths:>15} {notes}")
    print(line, flush=True)
    if ratio is not None and ratio > tally.worst[0]:
        tally.worst = (ratio, line)


def _record_lama(row: str, runs: dict[str, ProcessRun], fd: ProcessRun, tally: Tally) -> float | None:
    """Keep a gbfs row's timings against lama-first; ours / lama-first (repeated run, wall time)."""
    if fd.seconds is None:
        return None
    if runs["ours"].seconds is None:
        tally.lama_failed.append(row)
        return None
    for ours in OURS:
        mine, cpu = runs[ours].seconds, runs[ours].cpu_seconds
        if mine is not None:
            tally.lama[ours, "wall"].append((row, mine, fd.seconds))
        if cpu is not None and fd.cpu_seconds is not None:
            tally.lama[ours, "cpu"].append((row, cpu, fd.cpu_seconds))
    searched, fd_searched = runs["ours"].search_seconds, fd.search_seconds
    if searched is not None and fd_searched:
        # A search under a millisecond is reported as such: the ratio of two such times says nothing.
        tally.lama["ours", "search"].append((row, max(searched, 0.001), max(fd_searched, 0.001)))
    return runs["ours"].seconds / fd.seconds


def _fmt(value: float | None) -> str:
    return "-" if value is None else f"{value:.3f}"
