"""Whole-process wall time: each planner started as a fresh process, as a user runs it.

For each problem and search, our ``pddl/activity_planning.py``, pyperplan's
command line and Fast Downward's driver are started in turn (alternating, so
that a slow spell of a loaded machine hits all three alike), ``rounds`` times;
the median wall time of each is reported with the plan length it printed.
Python's byte code caches and our Lark grammar cache are warm (one run before
timing), as they are for anyone past their first run; nothing else is shared
between runs.

Pairings (ours / pyperplan / Fast Downward):

- ``bfs``: breadth-first / ``-s bfs`` / ``astar(blind())``
- ``astar``: A* with h_max / ``-s astar -H hmax`` / ``astar(hmax())``
- ``gbfs``: GBFS with h_FF and alternating preferred queues / ``-s gbf -H hff`` (plain) /
  ``--alias lama-first`` (its best satisficing configuration: the gap to it, not a like-for-like)
"""

from __future__ import annotations

import json
import math
import os
import re
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


def _command(planner: str, search: str, domain: Path, problem: Path, workdir: Path, fd_script: Path | None,
             timeout: float) -> list[str]:
    if planner == "ours":
        return [sys.executable, str(ENTRY_SCRIPT), str(problem), "--domain", str(domain), "--planner", search,
                "--json", "--timeout", str(timeout)]
    if planner == "pyperplan":
        return [sys.executable, "-m", "pyperplan", *PYPERPLAN_ARGS[search], str(domain), str(problem)]
    assert fd_script is not None
    alias, value = FAST_DOWNWARD_ARGS[search]
    head = [sys.executable, str(fd_script), "--plan-file", str(workdir / "fd.plan")]
    return [*head, alias, value, str(domain), str(problem)] if alias == "--alias" else [
        *head, str(domain), str(problem), alias, value]


def _plan_length(planner: str, completed: subprocess.CompletedProcess[str]) -> int | None:
    if planner == "ours":
        if completed.returncode != 0:
            return None
        length = json.loads(completed.stdout)["results"][0]["length"]
        return int(length) if length is not None else None
    text = completed.stdout + completed.stderr
    pattern = r"Plan length: (\d+)" if planner == "pyperplan" else r"Plan length: (\d+) step"
    match = re.search(pattern, text)
    return int(match.group(1)) if match else None


def _run_once(command: list[str], planner: str, workdir: Path,
              timeout: float) -> tuple[float | None, int | None]:
    start = time.perf_counter()
    try:
        # pyperplan's grounding iterates over sets: a fixed hash seed makes its rows reproducible.
        completed = subprocess.run(command, capture_output=True, text=True, cwd=workdir, timeout=timeout,
                                   env={**os.environ, "PYTHONHASHSEED": "0"})
    except subprocess.TimeoutExpired:
        return None, None
    seconds = time.perf_counter() - start
    length = _plan_length(planner, completed)
    return (seconds if length is not None else None), length


def compare_processes(domain: Path, problem: Path, search: str, workdir: Path, fd_script: Path | None,
                      timeout: float, rounds: int) -> dict[str, ProcessRun]:
    """Median wall time per planner over ``rounds`` alternating fresh-process runs (fewer for slow rows)."""
    planners = ["ours", "pyperplan"] + (["fd"] if fd_script else [])
    commands = {p: _command(p, search, domain, problem, workdir, fd_script, timeout) for p in planners}
    samples: dict[str, list[float]] = {p: [] for p in planners}
    lengths: dict[str, int | None] = dict.fromkeys(planners)
    failed: set[str] = set()
    for round_index in range(rounds):
        for planner in planners:
            if planner in failed:
                continue
            seconds, length = _run_once(commands[planner], planner, workdir, timeout + 5)
            if seconds is None:
                failed.add(planner)
                continue
            samples[planner].append(seconds)
            lengths[planner] = length
        slowest = max((s[0] for s in samples.values() if s), default=0.0)
        if round_index == 0 and slowest > 5.0:
            break  # a slow row: one round is measurement enough, and keeps the run short
    runs = {}
    for planner in planners:
        if samples[planner]:
            runs[planner] = ProcessRun(statistics.median(samples[planner]), lengths[planner])
        else:
            runs[planner] = ProcessRun(None, None, f"{planner}: no plan within {timeout:g} s")
    return runs


def geometric_mean(values: list[float]) -> float:
    return math.exp(sum(math.log(v) for v in values) / len(values))


def process_table(rows: list[tuple[str, Path, Path, tuple[str, ...]]], workdir: Path, fd_script: Path | None,
                  timeout: float, rounds: int) -> None:
    """Print the whole-process table for (name, domain, problem, searches) rows, and a summary."""
    header = (f"{'problem':22} {'search':6} {'ours s':>7} {'pp s':>7} {'pp/ours':>7} {'FD s':>7} "
              f"{'len ours/pp/FD':>15}")
    print("whole process: median wall time of fresh processes, alternating "
          f"(up to {rounds} rounds; FD = lama-first for gbfs)")
    print(header)
    print("-" * len(header))
    ratios: list[tuple[str, float]] = []
    notes: list[str] = []
    for name, domain, problem, searches in rows:
        for search in searches:
            if search not in PROCESS_SEARCHES:
                continue
            runs = compare_processes(domain, problem, search, workdir, fd_script, timeout, rounds)
            ours, peer = runs["ours"], runs["pyperplan"]
            fd = runs.get("fd")
            ratio = peer.seconds / ours.seconds if ours.seconds and peer.seconds else None
            if ratio is not None:
                ratios.append((f"{name} {search}", ratio))
            lengths = "/".join("-" if r.length is None else str(r.length) for r in runs.values())
            shown = f"{ratio:.2f}" if ratio is not None else "-"
            row_notes = " ".join(r.note for r in runs.values() if r.note)
            if search in ("bfs", "astar"):
                optimal = {r.length for r in runs.values() if r.length is not None}
                if len(optimal) > 1:
                    row_notes += " LENGTHS DIFFER"
            print(f"{name:22} {search:6} {_fmt(ours.seconds):>7} {_fmt(peer.seconds):>7} {shown:>7} "
                  f"{_fmt(fd.seconds if fd else None):>7} {lengths:>15} {row_notes}", flush=True)
            if ours.seconds is None:
                notes.append(f"{name} {search}: ours found no plan ({ours.note})")
    if ratios:
        values = [r for _, r in ratios]
        slower = [label for label, r in ratios if r < 1.0]
        print(f"\nwhole process, pyperplan / ours: geometric mean {geometric_mean(values):.2f}x, "
              f"minimum {min(values):.2f}x over {len(values)} rows both solved; "
              f"slower on: {', '.join(slower) if slower else 'none'}")
    for note in notes:
        print(note)


def _fmt(value: float | None) -> str:
    return "-" if value is None else f"{value:.3f}"
