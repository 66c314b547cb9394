"""Trajectory optimisation on the kitchen's free-space motions: which formulation is collision-free,
and how fast with Drake's distances against the sphere model's clearance?

Every query of the ``kitchen`` set of ``benchmarks/motion.py`` (the moves of the
kitchen task's BFS plans) is solved by seven variants. Variants 1-5 optimise
against Drake's model of the query's scene (minimum signed distance and gradient,
5 mm margin as in ``DEFAULT_SETTINGS``); sampling plans with the same Drake model
keeping the pipeline's 3 mm planning margin (none when an end is closer), exactly
as ``refine_action`` sets it up. Whatever a variant returns is verified the same
way: start and goal held, and the query's own PyBullet checker finds no
collision at every 0.005 rad along the path (``check_path_densely``).

1. ``original``: the class project's program, N=50 waypoints, no collision
   constraints, from the straight line;
2. ``straight``: ours (``DEFAULT_SETTINGS``) from the straight line, one attempt;
3. ``rrt warm``: ours warm-started from variant 6's path only (its CPU time
   includes planning that path);
4. ``full, Drake``: ``OptimizingMotionBackend().solve`` planning with Drake's
   model alone (``--collision-model drake``): Drake's distances, from the
   straight line when it is free, else from its own RRT-Connect path;
5. ``sparse``: ours with N=25 and no samples between waypoints, from the
   straight line;
6. ``rrt``: ``SamplingMotionBackend`` (RRT-Connect + shortcut), the yardstick;
7. ``full, spheres``: the back end as the pipeline runs it by default, planning
   with the sphere model in front of Drake's: the sphere model's smooth
   clearance first, Drake's distances only as the last attempt. Variants 4 and 7
   side by side are what the sphere model buys.

N is raised to what ``max_step`` needs for long moves, as the back end does.
"solver success" is what the solver (or back end) reports, "verified" what the
dense check accepts; medians of CPU s are over all queries (failures cost time
too), of length over verified paths, of length / rrt over queries both solved.
A query is "hard" when its straight line collides; ", hard" columns count those
only. Deterministic for a seed.

    .venv/bin/python benchmarks/trajopt.py                        # 16 queries x seeds 0 and 1
    .venv/bin/python benchmarks/trajopt.py --queries 24 --per-query
    .venv/bin/python benchmarks/trajopt.py --queries 8 --seeds 3
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from motion import MotionQuery, kitchen_queries  # benchmarks/motion.py, beside this script

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.motion import (
    ConfigurationSpace,
    InvalidMotionQueryError,
    JointConfiguration,
    JointPath,
    check_path_densely,
    path_length,
)
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker
from kitchen_tamp.motion.trajopt.program import (
    Clearance,
    SignedDistanceFunction,
    TrajectoryOptimizationSettings,
    one_at_a_time,
)
from kitchen_tamp.motion.trajopt.solver import nonlinear_solver, optimize_trajectory
from kitchen_tamp.refinement.motion_backend import (
    MotionSolution,
    SamplingMotionBackend,
)
from kitchen_tamp.refinement.optimizing_backend import OptimizingMotionBackend
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from kitchen_tamp.refinement.refine_action import PLANNING_MARGIN
from kitchen_tamp.world import PyBulletCollisionChecker
from kitchen_tamp.world.scene_description import describe_collision_checker

ORIGINAL_SETTINGS = replace(DEFAULT_SETTINGS, num_waypoints=50, samples_between_waypoints=0)
"""The class project's shape; its collision constraint is switched off by `_no_obstacles`."""
SPARSE_SETTINGS = replace(DEFAULT_SETTINGS, num_waypoints=25, samples_between_waypoints=0)


@dataclass(frozen=True)
class Outcome:
    """One variant on one query."""

    solver_success: bool
    verified: bool
    cpu_s: float
    path_length: float
    """Joint-space length (rad) of the returned path; nan when there is none."""
    detail: str = ""


@dataclass(frozen=True, eq=False)
class Case:
    """A query with the models the variants plan and verify with."""

    query: MotionQuery
    strict: PyBulletCollisionChecker
    planning: DrakeCollisionChecker
    spheres: SphereScreenedChecker
    """The pipeline's default planning model: the sphere model in front of ``planning``."""
    space: ConfigurationSpace
    seed: tuple[int, int]
    hard: bool
    reference: MotionSolution | None = None
    reference_cpu_s: float = 0.0


@dataclass(frozen=True)
class QueryRecord:
    """What the tables need of a query once its models are dropped (they hold Drake plants)."""

    name: str
    seed: int
    hard: bool


def _no_obstacles(q: JointConfiguration) -> tuple[float, JointConfiguration]:
    """A signed distance that is always far above any margin: no collision constraint at all."""
    return 1.0, np.zeros(len(q))


def _verified(path: JointPath, case: Case) -> bool:
    ends_held = np.allclose(path[0], case.query.start) and np.allclose(path[-1], case.query.goal)
    return ends_held and check_path_densely(path, case.strict, JUDGE_RESOLUTION_RAD).collision_free


def _enough_waypoints(
    settings: TrajectoryOptimizationSettings, start: JointConfiguration, goal: JointConfiguration
) -> TrajectoryOptimizationSettings:
    """``settings`` with N raised so that ``max_step`` can reach the goal (the back end's rule)."""
    needed = math.ceil(float(np.max(np.abs(goal - start))) / settings.max_step) + 1
    return replace(settings, num_waypoints=max(needed, settings.num_waypoints))


def _optimise(
    case: Case,
    settings: TrajectoryOptimizationSettings,
    signed_distance: SignedDistanceFunction,
    guide: JointPath | None = None,
    extra_cpu_s: float = 0.0,
) -> Outcome:
    """One call of ``optimize_trajectory``; verified only if the solver reports success."""
    start, goal = case.query.start, case.query.goal
    settings = _enough_waypoints(settings, start, goal)
    clock = time.process_time()
    try:
        clearance: Clearance = one_at_a_time(signed_distance)
        result = optimize_trajectory(start, goal, case.space, clearance, settings, initial_path=guide)
    except InvalidMotionQueryError as error:
        return Outcome(False, False, time.process_time() - clock + extra_cpu_s, math.nan, str(error))
    cpu_s = time.process_time() - clock + extra_cpu_s
    detail = f"N={settings.num_waypoints} {result.solution_status}"
    if not result.success:
        return Outcome(False, False, cpu_s, math.nan, detail)
    return Outcome(True, _verified(result.waypoints, case), cpu_s, path_length(result.waypoints), detail)


def run_original(case: Case) -> Outcome:
    return _optimise(case, ORIGINAL_SETTINGS, _no_obstacles)


def run_straight(case: Case) -> Outcome:
    return _optimise(case, DEFAULT_SETTINGS, case.planning.signed_distance)


def run_rrt_warm_start(case: Case) -> Outcome:
    reference = case.reference
    if reference is None or reference.path is None:
        return Outcome(False, False, case.reference_cpu_s, math.nan, "no rrt path")
    return _optimise(
        case, DEFAULT_SETTINGS, case.planning.signed_distance, reference.path, case.reference_cpu_s
    )


def run_full(case: Case) -> Outcome:
    return _run_backend(case, case.planning)


def run_full_spheres(case: Case) -> Outcome:
    return _run_backend(case, case.spheres)


def _run_backend(case: Case, planning: DrakeCollisionChecker | SphereScreenedChecker) -> Outcome:
    clock = time.process_time()
    solution = OptimizingMotionBackend().solve(
        case.query.start, case.query.goal, planning, case.strict, np.random.default_rng(case.seed)
    )
    cpu_s = time.process_time() - clock
    attempts = solution.figures.get("attempts")
    solver_success = isinstance(attempts, list) and any(a.get("solver_success") for a in attempts)
    if solution.path is None:
        return Outcome(solver_success, False, cpu_s, math.nan, solution.status)
    detail = f"attempt {solution.attempts}"
    return Outcome(True, _verified(solution.path, case), cpu_s, path_length(solution.path), detail)


def run_sparse(case: Case) -> Outcome:
    return _optimise(case, SPARSE_SETTINGS, case.planning.signed_distance)


def run_rrt(case: Case) -> Outcome:
    """The yardstick; it runs first and its path warm-starts ``run_rrt_warm_start``."""
    reference = case.reference
    if reference is None or reference.path is None:
        return Outcome(False, False, case.reference_cpu_s, math.nan, "unsolved")
    verified = _verified(reference.path, case)
    return Outcome(True, verified, case.reference_cpu_s, path_length(reference.path))


FULL_DRAKE = "4 full back end, Drake distances"
FULL_SPHERES = "7 full back end, sphere clearance (the pipeline's)"
VARIANTS: dict[str, Callable[[Case], Outcome]] = {
    "1 original (N=50, no collision constraint)": run_original,
    "2 ours, straight line only": run_straight,
    "3 ours, RRT-Connect warm start only": run_rrt_warm_start,
    FULL_DRAKE: run_full,
    "5 sparse (N=25, no samples between)": run_sparse,
    "6 RRT-Connect + shortcut": run_rrt,
    FULL_SPHERES: run_full_spheres,
}
YARDSTICK = "6 RRT-Connect + shortcut"


def prepare(query: MotionQuery, seed: tuple[int, int]) -> Case:
    """The query's Drake model with the pipeline's planning margin, and the yardstick's path."""
    if not isinstance(query.checker, PyBulletCollisionChecker):
        raise TypeError(f"{query.name}: expected a PyBullet checker, got {type(query.checker).__name__}")
    strict = query.checker
    description = describe_collision_checker(strict)
    margin = PLANNING_MARGIN
    planning = DrakeCollisionChecker(description, margin=margin)
    if not planning.is_valid(np.stack([query.start, query.goal])).all():
        margin = 0.0  # an end is closer: no slack
        planning = DrakeCollisionChecker(description, margin=margin)
    spheres = SphereScreenedChecker(SphereCollisionChecker(description, margin=margin), planning)
    straight = np.stack([query.start, query.goal])
    hard = not check_path_densely(straight, strict, JUDGE_RESOLUTION_RAD).collision_free
    space = ConfigurationSpace(planning.lower, planning.upper)
    case = Case(query, strict, planning, spheres, space, seed, hard)
    clock = time.process_time()
    reference = SamplingMotionBackend().solve(
        query.start, query.goal, planning, strict, np.random.default_rng(seed)
    )
    return replace(case, reference=reference, reference_cpu_s=time.process_time() - clock)


@dataclass(frozen=True)
class Summary:
    variant: str
    solver_success: float
    verified: float
    solver_ok_but_collides: int
    verified_hard: float
    median_cpu_s: float
    median_cpu_s_hard: float
    median_length: float
    median_ratio: float
    median_ratio_hard: float


def _median(values: Sequence[float]) -> float:
    return statistics.median(values) if values else math.nan


def summarise(variant: str, cases: Sequence[QueryRecord], results: dict[str, list[Outcome]]) -> Summary:
    runs, yardstick = results[variant], results[YARDSTICK]
    hard = [run for run, case in zip(runs, cases, strict=True) if case.hard]
    ratios = {
        index: run.path_length / ref.path_length
        for index, (run, ref) in enumerate(zip(runs, yardstick, strict=True))
        if run.verified and ref.verified and ref.path_length > 0.0
    }
    return Summary(
        variant=variant,
        solver_success=sum(run.solver_success for run in runs) / len(runs),
        verified=sum(run.verified for run in runs) / len(runs),
        solver_ok_but_collides=sum(run.solver_success and not run.verified for run in runs),
        verified_hard=sum(run.verified for run in hard) / len(hard) if hard else math.nan,
        median_cpu_s=_median([run.cpu_s for run in runs]),
        median_cpu_s_hard=_median([run.cpu_s for run in hard]),
        median_length=_median([run.path_length for run in runs if run.verified]),
        median_ratio=_median(list(ratios.values())),
        median_ratio_hard=_median([r for index, r in ratios.items() if cases[index].hard]),
    )


def _cell(value: float, spec: str) -> str:
    return "-" if math.isnan(value) else format(value, spec)


def format_table(summaries: Sequence[Summary], queries: int, hard: int) -> str:
    header = (
        "| variant | solver success | verified | solver ok, collides | "
        f"verified on hard ({hard}) | median CPU s | CPU s, hard | median length (rad) | length / RRT | "
        "length / RRT, hard |"
    )
    rows = [
        f"| {s.variant} | {s.solver_success:.0%} | {s.verified:.0%} | {s.solver_ok_but_collides}/{queries} "
        f"| {_cell(s.verified_hard, '.0%')} | {s.median_cpu_s:.3f} | {_cell(s.median_cpu_s_hard, '.3f')} "
        f"| {_cell(s.median_length, '.3f')} | {_cell(s.median_ratio, '.3f')} "
        f"| {_cell(s.median_ratio_hard, '.3f')} |"
        for s in summaries
    ]
    return "\n".join([header, "|---|" + "---:|" * 9, *rows])


def format_by_seed(
    seeds: Sequence[int], cases: Sequence[QueryRecord], results: dict[str, list[Outcome]]
) -> str:
    """Verified rate of each variant per seed."""
    header = "| verified | " + " | ".join(f"seed {seed}" for seed in seeds) + " |"
    rows = []
    for variant, runs in results.items():
        cells = []
        for seed in seeds:
            mine = [run.verified for run, case in zip(runs, cases, strict=True) if case.seed == seed]
            cells.append(f"{sum(mine)}/{len(mine)}")
        rows.append(f"| {variant} | " + " | ".join(cells) + " |")
    return "\n".join([header, "|---|" + "---:|" * len(seeds), *rows])


def format_per_query(cases: Sequence[QueryRecord], results: dict[str, list[Outcome]]) -> str:
    """One line per query: each variant as solver/verified flags, length and detail."""
    lines = []
    for index, case in enumerate(cases):
        cells = []
        for variant, runs in results.items():
            run = runs[index]
            flags = ("S" if run.solver_success else "-") + ("V" if run.verified else "-")
            cells.append(f"{variant[0]}:{flags} {run.path_length:.2f} {run.cpu_s:.2f}s {run.detail}".rstrip())
        lines.append(f"{case.name}{' (hard)' if case.hard else ''}\n    " + "\n    ".join(cells))
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n")[0])
    parser.add_argument("--queries", type=int, default=16, help="kitchen queries per seed")
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
    parser.add_argument("--per-query", action="store_true", help="also print every query's outcomes")
    args = parser.parse_args(argv)

    cases: list[QueryRecord] = []
    results: dict[str, list[Outcome]] = {variant: [] for variant in VARIANTS}
    wall = time.perf_counter()
    for seed in args.seeds:
        for index, query in enumerate(kitchen_queries(args.queries, seed)):
            case = prepare(query, (seed, index))
            cases.append(QueryRecord(query.name, seed, case.hard))
            for variant, run in VARIANTS.items():
                results[variant].append(run(case))
    hard = sum(case.hard for case in cases)
    print(
        f"{len(cases)} kitchen queries ({args.queries} per seed, seeds {' '.join(map(str, args.seeds))}), "
        f"{hard} hard; optimisation: {nonlinear_solver().solver_id().name()} "
        "(variants 1-5 on Drake signed distance), "
        f"margin {DEFAULT_SETTINGS.collision_margin} m; "
        f"verified: PyBullet, every {JUDGE_RESOLUTION_RAD} rad"
    )
    print()
    print(format_table([summarise(v, cases, results) for v in VARIANTS], len(cases), hard))
    print()
    print(format_by_seed(args.seeds, cases, results))
    print()
    for variant in (FULL_DRAKE, FULL_SPHERES):
        full = [run.detail for run in results[variant] if run.verified]
        attempts = {detail: full.count(detail) for detail in sorted(set(full))}
        print(f"{variant}, verified at: " + ", ".join(f"{d}: {n}" for d, n in attempts.items()))
    if args.per_query:
        print()
        print(format_per_query(cases, results))
    print(f"\nwall {time.perf_counter() - wall:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
