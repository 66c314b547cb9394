"""A stand-in for ``final_project.py`` in sweep tests (``--run-command``), fast and scripted by seed.

seed 0: solved and verified (exit 0); seed 1: dies without a report (exit 3, as an internal error);
seed 2: hangs (for timeouts); seed 3: a refinement failure with a report (exit 1);
any other seed: solved after ``FAKE_RUN_SLEEP_S`` seconds (default 0). Every call is appended to
the file named by ``FAKE_RUN_LOG``, if set, so tests can count how often a task ran.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path


def report(problem: str, mode: str, seed: int, solved: bool) -> dict[str, object]:
    return {
        "problem": Path(problem).name, "mode": mode, "seed": seed, "solved": solved,
        "plan": ["(open drawer)", "(pickUp spam countertop)"],
        "failure": None if solved else {"stage": "refinement", "reason": "SeSamE: out of samples"},
        "steps": [{"motion": {"path_length_rad": 1.25}}, {"motion": {"path_length_rad": 0.5}}],
        "bilevel": {"abstract_plans_tried": 1, "samples": 2 + seed, "backtracks": seed},
        "verification": {"verified": solved, "collision_free": True, "min_clearance_m": 0.002},
        "timing": {"startup_s": 0.5, "symbolic_s": 0.01, "motion_s": 1.0, "total_s": 2.0},
    }


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("mode")
    parser.add_argument("--problem", required=True)
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--no-video", action="store_true")
    args, _ = parser.parse_known_args()
    log = os.environ.get("FAKE_RUN_LOG")
    if log:
        with open(log, "a", encoding="utf-8") as stream:
            stream.write(f"{Path(args.problem).stem} {args.mode} {args.seed}\n")
    if args.seed == 1:
        print("Traceback (most recent call last):\nRuntimeError: fake crash", file=sys.stderr)
        return 3
    if args.seed == 2:
        time.sleep(600)
    if args.seed >= 4:
        time.sleep(float(os.environ.get("FAKE_RUN_SLEEP_S", "0")))
    solved = args.seed != 3
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "report.json").write_text(json.dumps(report(args.problem, args.mode, args.seed, solved)))
    return 0 if solved else 1


if __name__ == "__main__":
    sys.exit(main())
