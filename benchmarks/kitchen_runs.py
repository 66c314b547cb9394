"""The whole kitchen pipeline over problems x seeds: success, verification and time breakdown.

    .venv/bin/python benchmarks/kitchen_runs.py                    # rrt, both problems, seeds 0..19
    .venv/bin/python benchmarks/kitchen_runs.py --seeds 5 --mode rrt --problem problem.pddl

Each run is ``final_project.py MODE --no-video`` in its own process (as a user runs it);
its report gives the verdict and the timing. Prints one row per problem with the
success rate, minimum clearance and median seconds per stage.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
STAGES = ("startup_s", "symbolic_s", "skills_s", "motion_s", "verification_s", "total_s")


def run_once(mode: str, problem: str, seed: int, out: Path) -> dict[str, object]:
    """One run's report (with its exit code), or a stand-in report if none was written."""
    command = [sys.executable, str(ROOT / "final_project.py"), mode, "--problem", problem,
               "--seed", str(seed), "--out", str(out), "--no-video"]
    completed = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    report_path = out / "report.json"
    if not report_path.exists():
        return {"exit": completed.returncode, "solved": False, "failure": completed.stderr.strip()[-200:]}
    report: dict[str, object] = json.loads(report_path.read_text())
    report["exit"] = completed.returncode
    return report


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--mode", default="rrt", choices=("rrt", "optimizes"))
    parser.add_argument("--problem", action="append", help="problem(s) (default: both kitchen problems)")
    parser.add_argument("--seeds", type=int, default=20, help="seeds 0..N-1 (default 20)")
    args = parser.parse_args(argv)
    problems = args.problem or ["problem.pddl", "problem_hard.pddl"]
    print("| problem | mode | solved+verified | min clearance mm | "
          + " | ".join(f"median {s}" for s in STAGES) + " | max total_s |")
    print("|---|---|---|---|" + "---|" * len(STAGES) + "---|")
    failed_any = False
    with tempfile.TemporaryDirectory() as tmp:
        for problem in problems:
            reports = []
            for seed in range(args.seeds):
                report = run_once(args.mode, problem, seed, Path(tmp) / f"{problem}-{seed}")
                reports.append(report)
                if not report.get("solved"):
                    failed_any = True
                    print(f"  seed {seed}: exit {report['exit']}: {report.get('failure')}", file=sys.stderr)
            solved = [r for r in reports if r.get("solved")]
            timings = [r.get("timing", {}) for r in solved]
            medians = [
                statistics.median(float(t.get(s, 0.0)) for t in timings) if timings else float("nan")
                for s in STAGES
            ]
            clearances = [float(r["verification"]["min_clearance_m"]) for r in solved]  # type: ignore[index]
            worst = max((float(t.get("total_s", 0.0)) for t in timings), default=float("nan"))
            print(f"| {problem} | {args.mode} | {len(solved)}/{len(reports)} | "
                  f"{1000 * min(clearances, default=float('nan')):.1f} | "
                  + " | ".join(f"{m:.2f}" for m in medians) + f" | {worst:.2f} |", flush=True)
    return 1 if failed_any else 0


if __name__ == "__main__":
    sys.exit(main())
