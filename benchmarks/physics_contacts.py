"""Physics verdicts of saved runs under both contact models: GJK/EPA and polyhedral.

    python benchmarks/physics_contacts.py out/sat-rrt out/sat-opt [--jobs 2]

Every run folder of the sweeps (``OUT/runs/*`` with a ``trajectory.json``) is judged by
the kinematic judge and then executed under physics with ``polyhedral_contacts`` off and
on, each execution in a fresh process (PyBullet keeps the meshes it has read, with the
contact features of their first load, for the rest of a process). No re-plan after a
drift: the verdict is on the saved plan. Prints one row per problem and mode (runs,
verified under each model, median physics CPU seconds of each) and every run whose
verdicts differ, with physics' first problem.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from collections import defaultdict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace
from pathlib import Path

MODELS = ("gjk", "polyhedral")


def execute_one(trajectory_file: Path, model: str, problem: Path | None = None) -> dict[str, object]:
    """Judge a saved run in this process under ``model``, against ``problem`` (with the domain
    and scene beside it) or else the files the run recorded."""
    from kitchen_tamp.execute import read_trajectory
    from kitchen_tamp.execute.physics.execution import execute_under_physics, judged_pairs
    from kitchen_tamp.execute.physics.verdict import DEFAULT_CONFIGURATION
    from kitchen_tamp.execute.verification import verify_trajectory
    from kitchen_tamp.kitchen import build_kitchen_for_task
    from kitchen_tamp.kitchen.scene.choice import choose_scene
    from kitchen_tamp.planning import load_task

    run = read_trajectory(trajectory_file)
    choice = choose_scene(run.problem, run.scene, run.domain) if problem is None else choose_scene(problem)
    task, kitchen_map = load_task(choice.problem, choice.domain), choice.kitchen_map()
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as fresh:
        verification = verify_trajectory(fresh, task, run.trajectory)
    settings = replace(DEFAULT_CONFIGURATION.settings, polyhedral_contacts=model == "polyhedral")
    clock = time.process_time()
    physics = execute_under_physics(
        task, judged_pairs(run.trajectory, verification), kitchen_map,
        replace(DEFAULT_CONFIGURATION, settings=settings),
    )
    return {"kinematic": verification.verified, "physics": physics.verified,
            "cpu_s": time.process_time() - clock, "problems": physics.problems}


def execute_in_child(run_dir: Path, model: str) -> dict[str, object]:
    command = [sys.executable, __file__, "--one", str(run_dir / "trajectory.json"), model]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        crash = f"crashed: {done.stderr[-200:]}"
        return {"kinematic": False, "physics": False, "cpu_s": 0.0, "problems": [crash]}
    result: dict[str, object] = json.loads(done.stdout.splitlines()[-1])
    return result


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweeps", nargs="*", type=Path, help="evaluate output folders")
    parser.add_argument("--jobs", type=int, default=2, help="executions at once")
    parser.add_argument("--one", nargs=2, metavar=("TRAJECTORY", "MODEL"),
                        help="judge one saved run under MODEL (gjk or polyhedral) in this process "
                        "and print its verdicts as JSON")
    parser.add_argument("--problem", type=Path, help="with --one: judge against this problem file")
    args = parser.parse_args()
    if args.one:
        if args.one[1] not in MODELS:
            print(f"error: --one: unknown contact model {args.one[1]!r} (one of {', '.join(MODELS)})",
                  file=sys.stderr)
            return 2
        print(json.dumps(execute_one(Path(args.one[0]), args.one[1], args.problem)))
        return 0
    folders = (d for sweep in args.sweeps for d in (sweep / "runs").glob("*"))
    runs = sorted(d for d in folders if (d / "trajectory.json").exists())
    if not runs:
        print("error: no run folders with a trajectory.json under the sweeps given", file=sys.stderr)
        return 2
    tasks = [(run, model) for run in runs for model in MODELS]
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda task: execute_in_child(*task), tasks))
    verdicts = {task: result for task, result in zip(tasks, results, strict=True)}
    groups: dict[str, list[Path]] = defaultdict(list)
    for run in runs:
        groups[run.name.rsplit("-seed", 1)[0]].append(run)
    print("| problem and mode | runs | verified, gjk | polyhedral | physics CPU s, gjk | polyhedral |")
    print("|---|---|---|---|---|---|")
    for group, members in sorted(groups.items()):
        row = [group, str(len(members))]
        row += [str(sum(bool(verdicts[(r, m)]["physics"]) for r in members)) for m in MODELS]
        for model in MODELS:
            seconds = [float(str(verdicts[(r, model)]["cpu_s"])) for r in members]
            row.append(f"{statistics.median(seconds):.2f}")
        print("| " + " | ".join(row) + " |")
    for run in runs:
        gjk, polyhedral = (verdicts[(run, m)] for m in MODELS)
        if gjk["physics"] != polyhedral["physics"]:
            failed = "gjk" if polyhedral["physics"] else "polyhedral"
            problems = verdicts[(run, failed)]["problems"]
            first = problems[0] if isinstance(problems, list) and problems else ""
            print(f"{run.name}: fails under {failed} only: {first}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
