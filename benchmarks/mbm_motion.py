"""MotionBenchMaker's Panda problems: our RRT-Connect + shortcut against OMPL's RRTConnect, and
beside VAMP's published figures (``benchmarks/motion.py --query-set mbm``).

Per problem, three planners with the same time budget, in turns (the order rotates with the
problem): ours with the sphere model; OMPL's RRTConnect + simplifySolution asking the same
sphere model one configuration at a time; and OMPL with PyBullet's checker (the Panda and the
obstacles loaded into PyBullet, as a Python user of OMPL would set it up; its self pairs are
PyBullet's rule, two moving joints apart, a superset of MotionBenchMaker's matrix). Every path
is then re-checked by Drake's model of the same scene (the Panda's convex hulls and the exact
boxes, spheres and cylinders) at configurations ``JUDGE_RESOLUTION_RAD`` apart. A problem whose
start or goal Drake finds colliding is counted invalid (as VAMP counts problems its own model
rejects) and left out.

Budgets and times are CPU seconds of the planner alone (model building is not timed; the machine
is shared, so wall seconds would measure the neighbours); a planner that fails a problem is
counted at the budget, so medians and 95th percentiles are over every valid
problem. VAMP does not build from PyPI here (its build downloads its dependencies); its figures
are the published reference timings of ``resources/README.md`` in the vamp-planner 0.6.4
source distribution (Panda, MotionBenchMaker, RRT-Connect, AMD Ryzen 9 7950X, one core), which
give the 700 problems together, not per scenario.
"""

from __future__ import annotations

import json
import math
import statistics
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
from mbm_problems import ProblemsUnavailableError, load_problems, problems_directory
from motion import MotionQuery, Planned, Run, judged, plan_ompl, plan_ours

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.motion import CollisionChecker, ConfigurationSpace, RrtConnectHyperparameters
from kitchen_tamp.motion.motion_bench_maker import (
    MBM_FINGER_JOINTS,
    MBM_FINGER_OPENING,
    MBM_PANDA_LOWER,
    MBM_PANDA_UPPER,
    MbmFormatError,
    MbmProblem,
    mbm_scene,
)

VAMP_PUBLISHED_US = {"solve median": 35.0, "solve p95": 343.3, "total median": 99.0}
"""VAMP's RRT-Connect on MotionBenchMaker's 700 Panda problems (699 valid, all solved), microseconds:
planning time median and 95th percentile, planning + simplification median (vamp-planner 0.6.4,
resources/README.md, "MotionBenchMaker Reference Timings", Panda, AMD Ryzen 9 7950X)."""
MBM_SEARCH = RrtConnectHyperparameters(step_size=1.5, tree_balance=1.5, max_iterations=10**9)
"""Our RRT-Connect on these problems: steps of 1.5 rad (the kitchen's planner takes 1 rad; OMPL's
RRTConnect, by default a fifth of the space's extent, 2.68 rad here), a tree more than 1.5 times the
other's size waits its turn (the kitchen's planner alternates), bounded by the budget alone (not
10,000 iterations). Chosen on each scenario's first 40 problems and confirmed on all 100
(`benchmarks/mbm_search.py SCENARIO --problems 100 --steps 1 1.5 2 2.68 --balances 1.5`, docs/motion.md,
"A longer step"): against 1 rad, planning medians 8-29% lower on the table scenarios and the shelves,
12% higher on the cage; 2 rad and more lower the medians a little further but lengthen
bookshelf_small's tail (95th percentile 6 -> 36 ms). The balance: on bookshelf_small's 100 problems
strict turns took a median of 6.3 ms over the first 30 and missed problem 6, the balance 2.2 ms
(docs/motion.md, "A compiled loop, and the narrow passages")."""
PLANNERS = ("ours", "OMPL, same checker", "OMPL, PyBullet checker")


@dataclass(frozen=True, eq=False)
class MbmCase:
    """One problem with its models: the sphere model we plan with (Drake confirming its rejections
    near a start or goal it rejects, `EndConfirmedChecker`), Drake's exact model that judges, and
    PyBullet's checker for OMPL as its users set it up."""

    problem: MbmProblem
    query: MotionQuery
    planning: CollisionChecker
    exact: CollisionChecker
    pybullet: CollisionChecker


@contextmanager
def mbm_case(problem: MbmProblem) -> Iterator[MbmCase]:
    """The problem's models (PyBullet's scene is closed afterwards)."""
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
    from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
    from kitchen_tamp.motion.geometry.spheres.kernels.loading import serve_jit_kernels
    from kitchen_tamp.motion.geometry.spheres.screening import EndConfirmedChecker
    from kitchen_tamp.world import PANDA, Robot, Scene, make_collision_checker, panda_urdf_path

    # RRT-Connect's compiled loop loads numba anyway, and the JIT kernel answers OMPL's calls of one
    # configuration in about 6 us where the module compiled ahead of time, which unpacks the model's
    # arrays per call, takes 11: both planners check through the JIT kernel (the same verdicts).
    serve_jit_kernels()

    described = mbm_scene(problem, panda_urdf_path(), problems_directory() / "urdf")
    space = ConfigurationSpace(MBM_PANDA_LOWER, MBM_PANDA_UPPER)
    exact = DrakeCollisionChecker(described)
    ends = [problem.start, problem.goals[0]]
    planning = EndConfirmedChecker(SphereCollisionChecker(described), exact, ends, exact_is_bare=True)
    # The model is built here, outside every planner's clock: that includes the arrays the compiled
    # loop takes, which the sphere model packs on first use (0.12-0.14 ms on a table problem; the
    # arrays OMPL's calls go through are packed with the model), so no first query pays for them.
    planning.compiled_validity()
    query = MotionQuery(problem.name, problem.start, problem.goals[0], space, planning)
    with Scene() as scene:
        body = scene.load_urdf("panda", panda_urdf_path(), fixed_base=True)
        scene.load_urdf("obstacles", described.bodies[1].urdf_path, fixed_base=True)
        scene.set_joint_positions(body, MBM_FINGER_JOINTS, [MBM_FINGER_OPENING] * len(MBM_FINGER_JOINTS))
        robot = Robot(scene, body, PANDA)
        robot.lower, robot.upper = MBM_PANDA_LOWER.copy(), MBM_PANDA_UPPER.copy()
        yield MbmCase(problem, query, planning, exact, make_collision_checker(scene, robot))


def run_case(case: MbmCase, seed: int, budget_s: float, turn: int) -> dict[str, Run]:
    """Each planner on the case, starting with planner ``turn`` (mod 3); each path judged."""
    planners: dict[str, Callable[[], Planned]] = {
        PLANNERS[0]: lambda: plan_ours(case.query, case.planning, seed, budget_s, True, MBM_SEARCH),
        PLANNERS[1]: lambda: plan_ompl(case.query, case.planning, budget_s, cpu_budget=True),
        PLANNERS[2]: lambda: plan_ompl(case.query, case.pybullet, budget_s, cpu_budget=True),
    }
    order = PLANNERS[turn % 3 :] + PLANNERS[: turn % 3]
    return {name: judged(planners[name](), case.query, case.exact, JUDGE_RESOLUTION_RAD) for name in order}


def _percentile(values: Sequence[float], share: float) -> float:
    return float(np.percentile(np.asarray(values, dtype=float), share))


@dataclass(frozen=True)
class ScenarioSummary:
    """One planner on one scenario; a failure counts at the budget in the time columns."""

    success: float
    solve_median_s: float
    solve_p95_s: float
    total_median_s: float
    length_median: float


def summarise(runs: Sequence[Run], budget_s: float) -> ScenarioSummary:
    solve = [r.solve_cpu_s if r.solved else budget_s for r in runs]
    total = [r.total_cpu_s if r.solved else budget_s for r in runs]
    lengths = [r.path_length for r in runs if r.solved]
    return ScenarioSummary(
        success=sum(r.solved for r in runs) / len(runs),
        solve_median_s=statistics.median(solve),
        solve_p95_s=_percentile(solve, 95.0),
        total_median_s=statistics.median(total),
        length_median=statistics.median(lengths) if lengths else float("nan"),
    )


def _us(seconds: float) -> str:
    return f"{seconds * 1e6:,.0f}"


def format_scenario_table(
    results: dict[str, dict[str, list[Run]]], invalid: dict[str, int], budget_s: float
) -> str:
    """Per scenario and planner: valid problems, success, solve median and p95, total median (µs),
    path length; then OMPL's solve medians as multiples of ours, and ours of VAMP's."""
    header = (
        f"{'scenario':<17}{'planner':<24}{'valid':>6}{'success':>9}{'solve med':>11}{'solve p95':>11}"
        f"{'total med':>11}{'length':>8}"
    )
    lines = [f"CPU microseconds; a failure counts as the {budget_s:g} s budget", header, "-" * len(header)]
    everything: dict[str, list[Run]] = {name: [] for name in PLANNERS}
    for scenario, by_planner in results.items():
        summaries = {name: summarise(runs, budget_s) for name, runs in by_planner.items()}
        for name, summary in summaries.items():
            everything[name] += by_planner[name]
            count = len(by_planner[name])
            lines.append(
                f"{scenario:<17}{name:<24}{count:>6}{summary.success:>9.1%}{_us(summary.solve_median_s):>11}"
                f"{_us(summary.solve_p95_s):>11}{_us(summary.total_median_s):>11}{summary.length_median:>8.2f}"
            )
        ours = summaries[PLANNERS[0]].solve_median_s
        ratios = ", ".join(f"{name} {summaries[name].solve_median_s / ours:,.0f}x" for name in PLANNERS[1:])
        vamp = ours / (VAMP_PUBLISHED_US["solve median"] * 1e-6)
        lines.append(
            f"{'':<17}solve median as multiples of ours: {ratios}; ours is {vamp:,.0f}x VAMP's published "
            f"median; {invalid.get(scenario, 0)} invalid"
        )
    lines.append("-" * len(header))
    for name in PLANNERS:
        summary = summarise(everything[name], budget_s)
        lines.append(
            f"{'all':<17}{name:<24}{len(everything[name]):>6}{summary.success:>9.1%}"
            f"{_us(summary.solve_median_s):>11}{_us(summary.solve_p95_s):>11}"
            f"{_us(summary.total_median_s):>11}{summary.length_median:>8.2f}"
        )
    rejected = {
        name: sum(not r.solved and not math.isnan(r.path_length) for r in runs)
        for name, runs in everything.items()
    }
    lines.append(
        "paths returned but found colliding by Drake: " + ", ".join(f"{n} {k}" for n, k in rejected.items())
    )
    published = VAMP_PUBLISHED_US
    lines.append(
        f"{'all':<17}{'VAMP (published)':<24}{699:>6}{1.0:>9.1%}{published['solve median']:>11,.0f}"
        f"{published['solve p95']:>11,.0f}{published['total median']:>11,.0f}{'':>8}"
        "   (Ryzen 9 7950X, vamp-planner 0.6.4 resources/README.md)"
    )
    return "\n".join(lines)


def _save(path: Path, results: dict[str, dict[str, list[Run]]], invalid: dict[str, int]) -> None:
    """The runs as JSON (scenario -> planner -> runs), for ``--from-saved``."""
    data = {
        "invalid": invalid,
        "runs": {s: {n: [asdict(r) for r in runs] for n, runs in by.items()} for s, by in results.items()},
    }
    write_atomically(path, json.dumps(data))


def table_from_saved(paths: Sequence[Path], budget_s: float) -> int:
    """One table of runs saved by several ``--save`` runs (scenarios run in parallel processes)."""
    results: dict[str, dict[str, list[Run]]] = {}
    invalid: dict[str, int] = {}
    for path in paths:
        data = json.loads(path.read_text())
        invalid.update(data["invalid"])
        for scenario, by_planner in data["runs"].items():
            results[scenario] = {name: [Run(**run) for run in runs] for name, runs in by_planner.items()}
    print(f"MotionBenchMaker Panda, from {', '.join(p.name for p in paths)}")
    print(format_scenario_table(results, invalid, budget_s))
    return 0


def run_mbm(
    scenarios: Sequence[str], count: int, seed: int, budget_s: float, save: Path | None = None
) -> int:
    """Load, plan, judge and print (and save); exit status 2 when the problems cannot be had."""
    from ompl import util as ou

    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    ou.RNG.setSeed(seed + 1)
    try:
        problems = load_problems(scenarios, count)
    except (ProblemsUnavailableError, MbmFormatError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    results: dict[str, dict[str, list[Run]]] = {s: {name: [] for name in PLANNERS} for s in scenarios}
    invalid: dict[str, int] = {}
    clock = time.perf_counter()
    for turn, problem in enumerate(problems):
        with mbm_case(problem) as case:
            ends = np.stack([problem.start, problem.goals[0]])
            if not bool(np.all(case.exact.is_valid(ends))):
                invalid[problem.scenario] = invalid.get(problem.scenario, 0) + 1
                continue
            for name, run in run_case(case, seed + problem.index, budget_s, turn).items():
                results[problem.scenario][name].append(run)
    results = {s: r for s, r in results.items() if r[PLANNERS[0]]}
    print(
        f"MotionBenchMaker Panda: {len(problems)} problems ({count} per scenario), budget {budget_s:g} s, "
        f"seed {seed}, judged by Drake at {JUDGE_RESOLUTION_RAD} rad; {time.perf_counter() - clock:.0f} s"
    )
    print(format_scenario_table(results, invalid, budget_s))
    if save is not None:
        _save(save, results, invalid)
    return 0
