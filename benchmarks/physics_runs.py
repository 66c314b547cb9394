"""Kinematic and physics verdicts over modes x problems x seeds, and what physics adds to a run.

    nice .venv/bin/python benchmarks/physics_runs.py --out out/physics_runs          # plan and judge
    nice .venv/bin/python benchmarks/physics_runs.py --out out/physics_runs --replay # judge saved runs again

Each run is ``final_project.py MODE --no-video`` in its own process (with ``--replay``:
``final_project.py replay RUN_DIR --no-video`` on the trajectories a previous sweep kept
in ``--out``). Prints one row per mode and problem (runs refined, kinematic verdicts,
physics verdicts, the largest joint tracking error and re-plans under physics over the runs,
median seconds of physics and of the whole run, physics' share of the run) and then every
failure with its cause.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
PROBLEMS = ("problem.pddl", "problem_hard.pddl", "problem_baguette.pddl")
MODES = ("rrt", "optimizes")


def judge(mode: str, problem: str, seed: int, run_dir: Path, replay: bool) -> dict[str, object]:
    """One run's report with its exit code (a stand-in if the program wrote none)."""
    if replay:
        command = [sys.executable, str(ROOT / "final_project.py"), "replay", str(run_dir), "--no-video"]
        report_path = run_dir / "replay_report.json"
    else:
        command = [sys.executable, str(ROOT / "final_project.py"), mode, "--problem", problem,
                   "--seed", str(seed), "--out", str(run_dir), "--no-video"]
        report_path = run_dir / "report.json"
    if replay and not (run_dir / "trajectory.json").exists():
        return {"exit": None, "failure": {"stage": "refinement", "reason": "no trajectory was kept"}}
    completed = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    if not report_path.exists():
        crash = {"stage": "crash", "reason": completed.stderr[-300:]}
        return {"exit": completed.returncode, "failure": crash}
    report: dict[str, object] = json.loads(report_path.read_text())
    report["exit"] = completed.returncode
    return report


def verdict(section: object) -> bool | None:
    """A report section's ``verified``, or None when the section is absent."""
    return bool(section["verified"]) if isinstance(section, dict) else None


def cause(report: dict[str, object]) -> str:
    """Why a run is not physics-verified, in one line."""
    physics = report.get("physics")
    if isinstance(physics, dict) and physics.get("problems"):
        return "physics: " + "; ".join(str(p) for p in physics["problems"])
    failure = report.get("failure")
    if isinstance(failure, dict):
        return f"{failure.get('stage')}: {failure.get('reason')}"
    return f"exit {report.get('exit')}"


def summarize(rows: dict[tuple[str, str], list[tuple[int, dict[str, object]]]]) -> list[str]:
    """Print the table; return every failure with its cause."""
    failures: list[str] = []
    print("| mode | problem | seeds | refined | kinematic verified | physics verified | max tracking rad "
          "| re-plans | median physics s | median run s | physics share |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (mode, problem), runs in rows.items():
        reports = [report for _, report in runs]
        for seed, report in runs:
            if verdict(report.get("physics")) is not True:
                failures.append(f"{mode} {problem} seed {seed}: {cause(report)}")
        refined = [r for r in reports if r.get("verification") is not None]
        kinematic = [r for r in refined if verdict(r.get("verification"))]
        physical = [r for r in refined if verdict(r.get("physics"))]
        timed: list[dict[str, Any]] = [r["timing"] for r in refined if isinstance(r.get("timing"), dict)]  # type: ignore[misc]
        physics_s = [float(t["physics_s"]) for t in timed if "physics_s" in t]
        total_s = [float(t["total_s"]) for t in timed if "total_s" in t]
        shares = [p / t for p, t in zip(physics_s, total_s, strict=False) if t > 0.0]
        sections: list[dict[str, Any]] = [r["physics"] for r in refined if isinstance(r.get("physics"), dict)]  # type: ignore[misc]
        tracking = max((float(s.get("max_joint_error_rad", 0.0)) for s in sections), default=0.0)
        replans = sum(len(s.get("replans") or []) for s in sections)
        seeds = sorted(seed for seed, _ in runs)
        span = f"{seeds[0]}..{seeds[-1]}" if seeds else "-"
        print(f"| {mode} | {problem} | {span} | {len(refined)}/{len(reports)} "
              f"| {len(kinematic)}/{len(refined)} "
              f"| {len(physical)}/{len(refined)} | {tracking:.3f} | {replans} | {_median(physics_s)} "
              f"| {_median(total_s)} | {_median(shares)} |", flush=True)
    return failures


def _median(values: list[float]) -> str:
    return f"{statistics.median(values):.2f}" if values else "-"


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--mode", action="append", choices=MODES, help="mode(s) (default: both)")
    parser.add_argument("--problem", action="append", help="problem(s) (default: the three kitchen problems)")
    parser.add_argument("--seeds", type=int, default=20, help="seeds 0..N-1 (default 20)")
    parser.add_argument("--out", type=Path, required=True, help="folder that keeps every run")
    what = parser.add_mutually_exclusive_group()
    what.add_argument("--replay", action="store_true", help="judge the runs kept in --out again")
    what.add_argument("--resume", action="store_true", help="keep the reports of runs already in --out")
    what.add_argument("--summarize", action="store_true", help="only tabulate the reports kept in --out")
    args = parser.parse_args(argv)
    rows: dict[tuple[str, str], list[tuple[int, dict[str, object]]]] = {}
    modes = args.mode or MODES
    problems = args.problem or PROBLEMS
    for mode in modes:
        for problem in problems:
            rows[(mode, problem)] = []
    for seed in range(args.seeds):
        for mode in modes:
            for problem in problems:
                run_dir = args.out / f"{Path(problem).stem}-{mode}-seed{seed}"
                kept = run_dir / ("replay_report.json" if args.replay else "report.json")
                if args.summarize or (args.resume and kept.exists()):
                    if not kept.exists():
                        continue
                    report: dict[str, object] = json.loads(kept.read_text())
                else:
                    report = judge(mode, problem, seed, run_dir, args.replay)
                    line = f"{mode} {problem} seed {seed}: exit {report.get('exit')}"
                    print(line + ("" if verdict(report.get("physics")) else f", {cause(report)}"),
                          file=sys.stderr, flush=True)
                rows[(mode, problem)].append((seed, report))
    failures = summarize(rows)
    print("\nfailures:" if failures else "\nno failures")
    for line in failures:
        print(f"- {line}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
