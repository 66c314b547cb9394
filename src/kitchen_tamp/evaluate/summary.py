"""``summary.md`` of a sweep folder: success per problem and mode with 95% intervals, times, path
lengths, failure causes, and what became of the random problems; the plots beside it."""

from __future__ import annotations

import csv
import json
from collections.abc import Sequence
from pathlib import Path

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.evaluate.random_problems import MANIFEST_FILE, RANDOM_PROBLEMS_DIR
from kitchen_tamp.evaluate.results_table import RESULTS_FILE, read_rows
from kitchen_tamp.evaluate.success_statistics import GroupFigures, group_figures

SUMMARY_FILE = "summary.md"
RANDOM_GROUP = "random"
"""Rows of the random problems are also summarised together under this name."""

Rows = list[dict[str, str]]


def random_manifest(out_dir: Path) -> Rows:
    """The rows of ``problems/random_problems.csv`` (none if the sweep has no random problems)."""
    path = out_dir / RANDOM_PROBLEMS_DIR / MANIFEST_FILE
    if not path.exists():
        return []
    with path.open(newline="", encoding="utf-8") as stream:
        return list(csv.DictReader(stream))


def grouped(rows: Sequence[dict[str, str]], random_names: set[str]) -> dict[tuple[str, str], Rows]:
    """(problem, mode) -> rows, in first-seen order; random problems also pooled as ``random``."""
    groups: dict[tuple[str, str], Rows] = {}
    for row in rows:
        groups.setdefault((row["problem"], row["mode"]), []).append(row)
    for row in rows:
        if row["problem"] in random_names:
            groups.setdefault((f"{RANDOM_GROUP} ({len(random_names)} problems)", row["mode"]), []).append(row)
    return groups


def _seconds(value: float | None) -> str:
    return "-" if value is None else f"{value:.1f}"


def _table_row(problem: str, mode: str, figures: GroupFigures) -> str:
    low, high = figures.interval
    causes = ", ".join(f"{cause} {count}" for cause, count in figures.causes.most_common()) or "-"
    path = "-" if figures.median_path_rad is None else f"{figures.median_path_rad:.1f}"
    physics = "-" if not figures.physics_checked else f"{figures.physics_verified}/{figures.physics_checked}"
    plans, facts = (_count(value) for value in (figures.median_plans, figures.median_facts))
    return (f"| {problem} | {mode} | {figures.solved}/{figures.runs} | {100 * figures.rate:.0f}% "
            f"[{100 * low:.0f}, {100 * high:.0f}] | {_seconds(figures.median_time_s)} | "
            f"{_seconds(figures.p90_time_s)} | {plans} | {facts} | {path} | {physics} | {causes} |")


def _count(value: float | None) -> str:
    return "-" if value is None else f"{value:g}"


def success_table(groups: dict[tuple[str, str], Rows], random_names: set[str]) -> list[str]:
    """The markdown table of every group except single random problems."""
    lines = [
        "| problem | mode | solved | success [95% CI] | median s | p90 s | plans | facts learned | "
        "median path rad | physics ok | failures |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for (problem, mode), rows in groups.items():
        if problem not in random_names:
            lines.append(_table_row(problem, mode, group_figures(rows)))
    return lines


def random_section(manifest: Rows, rows: Sequence[dict[str, str]]) -> list[str]:
    """How many random problems laid out, had a plan, and were solved by the system."""
    if not manifest:
        return []
    names = {entry["problem"] for entry in manifest}
    solvable = {entry["problem"] for entry in manifest if entry["symbolically_solvable"] == "true"}
    by_problem: dict[str, Rows] = {}
    for row in rows:
        if row["problem"] in names:
            by_problem.setdefault(row["problem"], []).append(row)
    run = [name for name in names if name in by_problem]
    every = sum(all(r["status"] == "solved" for r in by_problem[name]) for name in run)
    never = sorted(name for name in run if not any(r["status"] == "solved" for r in by_problem[name]))
    first_try = sum(entry["layout_attempts"] == "1" for entry in manifest)
    lengths = sorted(int(entry["plan_length"]) for entry in manifest if entry["plan_length"])
    return [
        "## Random problems",
        "",
        f"- generated: {len(manifest)}, each laid out in the kitchen ({first_try} at the first start drawn)",
        f"- symbolically solvable: {len(solvable)}/{len(manifest)} "
        f"(shortest plans of {lengths[0]} to {lengths[-1]} actions)" if lengths else
        f"- symbolically solvable: 0/{len(manifest)}",
        f"- run in this sweep: {len(run)}; solved by the system with every seed: {every}, "
        f"with at least one: {len(run) - len(never)}",
        f"- solved with no seed: {', '.join(never) or 'none'}",
        "",
    ]


def _commands(out_dir: Path) -> list[str]:
    try:
        log = json.loads((out_dir / "sweep.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return []
    return [" ".join(entry["command"]) for entry in log if isinstance(entry, dict) and "command" in entry]


def summary_text(out_dir: Path, rows: Sequence[dict[str, str]], manifest: Rows) -> str:
    random_names = {entry["problem"] for entry in manifest}
    groups = grouped(rows, random_names)
    lines = [
        "# Sweep summary",
        "",
        f"{len(rows)} tasks from `{RESULTS_FILE}`. A task is solved when `final_project.py` exits 0 with a "
        "verified report. Success is over all tasks of a group with a 95% Wilson interval; times are "
        "wall seconds of the solved tasks (process start to exit); plans (abstract plans tried) and "
        "facts learned (from failures, fed back to the abstract search) are medians over the tasks "
        "that planned; path lengths are the solved tasks' joint-space length summed over the "
        "actions; failures are counted by cause (timeout, crashed, or the stage that failed).",
        "",
        *success_table(groups, random_names),
        "",
        *random_section(manifest, rows),
    ]
    commands = _commands(out_dir)
    if commands:
        lines += ["## Commands", "", "```sh", *commands, "```", ""]
    return "\n".join(lines)


def write_summary(out_dir: Path) -> list[Path]:
    """Write ``summary.md`` and the plots from the folder's ``results.csv``; the files written."""
    from kitchen_tamp.evaluate.plots import write_plots  # matplotlib only when a summary is made

    rows = read_rows(out_dir / RESULTS_FILE)
    manifest = random_manifest(out_dir)
    written = [write_atomically(out_dir / SUMMARY_FILE, summary_text(out_dir, rows, manifest))]
    groups = grouped(rows, {entry["problem"] for entry in manifest})
    pooled = {key: value for key, value in groups.items() if key[0] not in {e["problem"] for e in manifest}}
    written += write_plots(out_dir, pooled)
    return written
