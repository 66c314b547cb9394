"""What a user waits for ``final_project.py``: two checkouts, whole processes, alternating.

Each case starts ``final_project.py`` as a fresh process in each checkout in turn
(so that a slow spell of the shared machine hits both alike), with the checkout's
``src`` first on ``PYTHONPATH`` (so a checkout sharing another's virtual environment
still runs its own code), ``--runs`` times,
and prints the median wall time and CPU time (user + system, the process and its
children) of each, their ratio (base / ours), and the median of the phases the
run's ``report.json`` gives under ``timing``. Cases:

- ``warm``: ``rrt`` with the GIF and replay.html, user cache filled by one run
  before timing (as for anyone past their first run);
- ``no-video``: the same with ``--no-video``;
- ``optimizes``: ``optimizes`` with the GIF, warm;
- ``fresh``: a fresh ``git clone`` of the checkout's HEAD and an empty user cache
  per run, timed to the first verified result. The clone runs with the
  checkout's virtual environment (its ``src`` first on ``PYTHONPATH``), so
  nothing compiled or generated before is found: neither the user cache nor
  numba's cache beside the clone's sources. What the checkout's ``make install``
  prepares beyond installing packages (``python -m kitchen_tamp.cli.prepare``,
  where the checkout has it) is run in the clone first and timed apart, and the
  total is printed beside the first run.

``--same-reports`` runs both checkouts once per problem, mode and seed and says
whether each pair of reports is identical apart from ``timing`` and paths.

    python benchmarks/demo_time.py --base ../base-d566cf8 --runs 5 --cases warm no-video fresh optimizes
    python benchmarks/demo_time.py --base ../base-074b918 --same-reports --seeds 0 1 2
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CASES = {
    "warm": ("rrt", []),
    "no-video": ("rrt", ["--no-video"]),
    "optimizes": ("optimizes", []),
    "fresh": ("rrt", []),
}
"""Case -> mode and extra options of ``final_project.py``."""
PHASES = ("startup_s", "symbolic_s", "refinement_s", "skills_s", "checkers_s", "motion_s", "judge_replay_s",
          "verification_s", "physics_s", "physics_run_s", "rendering_s", "html_s", "pictures_wait_s", "gif_s",
          "joints_s", "other_s", "total_s")
PREPARE_MODULE = "kitchen_tamp.cli.prepare"
PATH_KEYS = ("problem_path", "domain_path", "scene_path", "inputs")
"""Report keys that name where the checkout is, not what the run did."""


@dataclass(frozen=True)
class Checkout:
    """A checkout with its own ``.venv`` (``make install``)."""

    label: str
    root: Path

    @property
    def python(self) -> Path:
        return self.root / ".venv" / "bin" / "python"


@dataclass
class Timings:
    """Per run: wall and CPU seconds, the report's timing, and install-time preparation."""

    wall: list[float] = field(default_factory=list)
    cpu: list[float] = field(default_factory=list)
    prepare: list[float] = field(default_factory=list)
    phases: dict[str, list[float]] = field(default_factory=dict)


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _timed(command: Sequence[str], cwd: Path, env: dict[str, str]) -> tuple[float, float, int]:
    """(wall s, CPU s, exit code) of one process."""
    cpu, clock = _children_cpu(), time.perf_counter()
    done = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True, check=False)
    wall = time.perf_counter() - clock
    if done.returncode != 0:
        print(f"  {' '.join(command)} exited {done.returncode}: {done.stderr.strip()[-400:]}")
    return wall, _children_cpu() - cpu, done.returncode


def _environment(cache: Path, source: Path | None = None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "PYTHONPATH")}
    env["XDG_CACHE_HOME"] = str(cache)
    if source is not None:
        env["PYTHONPATH"] = str(source)
    return env


def _fresh_clone(checkout: Checkout, scratch: Path) -> Path:
    clone = Path(tempfile.mkdtemp(prefix=f"clone-{checkout.label}-", dir=scratch))
    subprocess.run(["git", "-c", "advice.detachedHead=false", "clone", "--quiet", "--no-hardlinks",
                    str(checkout.root), str(clone)], check=True)
    return clone


def _run_once(checkout: Checkout, case: str, args: argparse.Namespace, scratch: Path,
              timings: Timings) -> None:
    mode, options = CASES[case]
    out = Path(tempfile.mkdtemp(prefix=f"out-{checkout.label}-", dir=scratch))
    if case == "fresh":
        root = _fresh_clone(checkout, scratch)
        env = _environment(Path(tempfile.mkdtemp(prefix="cache-", dir=scratch)), root / "src")
        if (root / "src" / Path(*PREPARE_MODULE.split("."))).with_suffix(".py").is_file():
            wall, _, _ = _timed([str(checkout.python), "-m", PREPARE_MODULE], root, env)
            timings.prepare.append(wall)
    else:
        root, env = checkout.root, _environment(scratch / f"cache-{checkout.label}", checkout.root / "src")
    command = [str(checkout.python), "final_project.py", mode, "--problem", args.problem,
               "--seed", str(args.seed), "--out", str(out), *options]
    wall, cpu, code = _timed(command, root, env)
    if code == 0:
        timings.wall.append(wall)
        timings.cpu.append(cpu)
        timing = json.loads((out / "report.json").read_text())["timing"]
        for phase in PHASES:
            if isinstance(timing.get(phase), float | int):
                timings.phases.setdefault(phase, []).append(float(timing[phase]))
    if case == "fresh":
        shutil.rmtree(root, ignore_errors=True)
    shutil.rmtree(out, ignore_errors=True)


def _median(values: list[float]) -> float:
    return statistics.median(values) if values else float("nan")


def _print_case(case: str, base: Timings, ours: Timings) -> None:
    print(f"\n{case}: median of {len(base.wall)} (base) and {len(ours.wall)} (ours) runs")
    print(f"  {'':16}{'base':>9}{'ours':>9}{'ratio':>8}")
    rows = [("wall s", base.wall, ours.wall), ("cpu s", base.cpu, ours.cpu)]
    if ours.prepare or base.prepare:
        rows.append(("install prep s", base.prepare, ours.prepare))
        totals = [_median(t.prepare or [0.0]) + _median(t.wall) for t in (base, ours)]
        rows.append(("prep + run s", [totals[0]], [totals[1]]))
    rows += [(phase, base.phases.get(phase, []), ours.phases.get(phase, [])) for phase in PHASES]
    for name, b, o in rows:
        mb, mo = _median(b), _median(o)
        ratio = f"{mb / mo:7.2f}x" if b and o and mo > 0 else ""
        print(f"  {name:16}{mb:9.2f}{mo:9.2f}{ratio}")


def time_cases(base: Checkout, ours: Checkout, args: argparse.Namespace, scratch: Path) -> None:
    for case in args.cases:
        results = {base.label: Timings(), ours.label: Timings()}
        if case != "fresh":
            for checkout in (base, ours):  # fill the user cache and numba's once, untimed
                _run_once(checkout, case, args, scratch, Timings())
        for run in range(args.runs):
            order = (base, ours) if run % 2 == 0 else (ours, base)
            for checkout in order:
                _run_once(checkout, case, args, scratch, results[checkout.label])
            walls = [f"{c.label} {results[c.label].wall[-1]:.2f} s"
                     for c in (base, ours) if results[c.label].wall]
            print(f"{case} run {run + 1}: " + ", ".join(walls), flush=True)
        print(f"load average {os.getloadavg()[0]:.1f}")
        _print_case(case, results[base.label], results[ours.label])


def _comparable(report: dict[str, object]) -> dict[str, object]:
    return {k: v for k, v in report.items() if k != "timing" and k not in PATH_KEYS}


def same_reports(base: Checkout, ours: Checkout, args: argparse.Namespace, scratch: Path) -> bool:
    """Runs both checkouts per problem, mode and seed; True when all reports agree apart from
    ``timing`` and paths."""
    all_same = True
    for problem in args.problems:
        for mode in args.modes:
            for seed in args.seeds:
                reports = []
                for checkout in (base, ours):
                    # the kitchen's folder too: the benchmark kitchens' problems share file names
                    name = "-".join(filter(None, (Path(problem).parent.name, Path(problem).stem)))
                    out = scratch / f"{checkout.label}-{name}-{mode}-{seed}"
                    command = [str(checkout.python), "final_project.py", mode, "--problem", problem,
                               "--seed", str(seed), "--out", str(out), "--no-video"]
                    env = _environment(scratch / f"cache-{checkout.label}", checkout.root / "src")
                    _timed(command, checkout.root, env)
                    reports.append(_comparable(json.loads((out / "report.json").read_text())))
                same = reports[0] == reports[1]
                all_same &= same
                differing = [k for k in reports[0] if reports[0].get(k) != reports[1].get(k)]
                verdict = "identical" if same else f"DIFFER in {differing}"
                print(f"{problem} {mode} seed {seed}: {verdict} (solved {reports[0]['solved']} / "
                      f"{reports[1]['solved']})", flush=True)
    return all_same


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--base", type=Path, required=True, help="the checkout to compare against")
    parser.add_argument("--ours", type=Path, default=REPO)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--cases", nargs="+", choices=list(CASES), default=["warm", "no-video"])
    parser.add_argument("--problem", default="problem.pddl")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--same-reports", action="store_true", help="compare reports instead of timing")
    parser.add_argument("--problems", nargs="+", default=["problem.pddl", "problem_hard.pddl"])
    parser.add_argument("--modes", nargs="+", default=["rrt", "optimizes"])
    parser.add_argument("--seeds", nargs="+", type=int, default=[0])
    parser.add_argument("--scratch", type=Path, default=None, help="where clones, caches and outputs go")
    args = parser.parse_args()
    base, ours = Checkout("base", args.base.resolve()), Checkout("ours", args.ours.resolve())
    scratch = args.scratch or Path(tempfile.mkdtemp(prefix="demo_time-"))
    scratch.mkdir(parents=True, exist_ok=True)
    print(f"base {base.root}, ours {ours.root}; scratch {scratch}")
    if args.same_reports:
        return 0 if same_reports(base, ours, args, scratch) else 1
    time_cases(base, ours, args, scratch)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
