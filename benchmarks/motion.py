"""Our RRT-Connect + shortcut against OMPL's RRTConnect + simplifySolution, in one run.

Both planners answer the same queries through the same collision checker, at
the same edge-check resolution, with the same time budget per query (planning
gets all of it, smoothing what planning left); OMPL calls the checker one
configuration at a time, ours in batches. Every returned path is re-checked
densely before it counts as a success. Per planner the table gives the success
rate, median CPU seconds of planning alone (solve), of smoothing alone and of
both (total), median path length after smoothing and collision checks, and
checks per CPU second; then ratios ours/OMPL and the project's bar.

    .venv/bin/python benchmarks/motion.py                      # planar 7-link arm
    .venv/bin/python benchmarks/motion.py --query-set joint_space_obstacles
    .venv/bin/python benchmarks/motion.py --query-set kitchen --checker drake --queries 24

A query set is a function (count, seed) -> list[MotionQuery] in QUERY_SETS.
The kitchen's queries are the free-space motions of the real task (see
`kitchen_queries`), checked by PyBullet or by the Drake model of the same scene.
"""

from __future__ import annotations

import argparse
import itertools
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion import (
    CollisionChecker,
    ConfigurationSpace,
    CountingSegmentChecker,
    RrtConnectHyperparameters,
    ShortcutHyperparameters,
    densify_path,
    path_length,
    plan_rrt_connect,
    shortcut_path,
)
from kitchen_tamp.motion.motion_bench_maker import MBM_SCENARIOS

EDGE_RESOLUTION = 0.01
"""Joint-space distance (rad) between checked configurations, for both planners."""

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class MotionQuery:
    """One planning problem: start and goal in a space, with its collision checker."""

    name: str
    start: FloatArray
    goal: FloatArray
    space: ConfigurationSpace
    checker: CollisionChecker
    judge: CollisionChecker | None = None
    """The checker OMPL plans with and every path is re-checked by (``checker`` when None)."""

    @property
    def judging_checker(self) -> CollisionChecker:
        return self.checker if self.judge is None else self.judge


class PlanarArmWorld:
    """A planar arm of `len(link_lengths)` revolute links among discs, checked in numpy."""

    def __init__(self, link_lengths: FloatArray, disc_centers: FloatArray, radii: FloatArray):
        self.link_lengths = link_lengths
        self.disc_centers = disc_centers
        self.radii = radii

    def is_valid(self, qs: FloatArray) -> npt.NDArray[np.bool_]:
        angles = np.cumsum(qs, axis=1)
        steps = self.link_lengths[:, np.newaxis] * np.stack([np.cos(angles), np.sin(angles)], -1)
        bases = np.cumsum(steps, axis=1) - steps  # (n, links, 2)
        link = steps[:, :, np.newaxis, :]  # (n, links, 1, 2)
        to_center = self.disc_centers[np.newaxis, np.newaxis] - bases[:, :, np.newaxis, :]
        along = np.clip(np.sum(to_center * link, axis=-1) / np.sum(link * link, axis=-1), 0.0, 1.0)
        gap = to_center - along[..., np.newaxis] * link
        clear = np.einsum("nlkc,nlkc->nlk", gap, gap) > self.radii**2
        return np.asarray(np.all(clear, axis=(1, 2)))

    def segment_valid(self, q0: FloatArray, q1: FloatArray) -> bool:
        return CountingSegmentChecker(self, EDGE_RESOLUTION).segment_valid(q0, q1)


class JointSpaceObstacleWorld:
    """Balls and axis-aligned boxes directly in joint space."""

    def __init__(self, ball_centers: FloatArray, ball_radii: FloatArray, boxes: FloatArray):
        self.ball_centers = ball_centers
        self.ball_radii = ball_radii
        self.boxes = boxes  # (k, 2, d): lower and upper corners

    def is_valid(self, qs: FloatArray) -> npt.NDArray[np.bool_]:
        offsets = qs[:, np.newaxis, :] - self.ball_centers[np.newaxis]
        outside_balls = np.all(np.sum(offsets**2, axis=-1) > self.ball_radii**2, axis=1)
        inside_box = np.all(
            (qs[:, np.newaxis] >= self.boxes[:, 0]) & (qs[:, np.newaxis] <= self.boxes[:, 1]),
            axis=-1,
        )
        return np.asarray(outside_balls & ~np.any(inside_box, axis=1))

    def segment_valid(self, q0: FloatArray, q1: FloatArray) -> bool:
        return CountingSegmentChecker(self, EDGE_RESOLUTION).segment_valid(q0, q1)


def _sample_queries(
    prefix: str,
    space: ConfigurationSpace,
    checker: CollisionChecker,
    count: int,
    rng: np.random.Generator,
) -> list[MotionQuery]:
    """Random valid start/goal pairs whose straight line collides."""
    queries: list[MotionQuery] = []
    segments = CountingSegmentChecker(checker, EDGE_RESOLUTION)
    while len(queries) < count:
        candidates = space.sample_uniform(rng, 64)
        valid = candidates[checker.is_valid(candidates)]
        for start, goal in zip(valid[0::2], valid[1::2], strict=False):
            if len(queries) < count and not segments.segment_valid(start, goal):
                queries.append(MotionQuery(f"{prefix}-{len(queries)}", start, goal, space, checker))
    return queries


def planar_arm_queries(count: int, seed: int) -> list[MotionQuery]:
    """A 7-link planar arm (reach 1) among eight discs."""
    rng = np.random.default_rng(seed)
    bearings = np.linspace(0.0, 2 * np.pi, 8, endpoint=False) + 0.3
    distances = np.array([0.45, 0.8, 0.55, 0.9, 0.5, 0.75, 0.6, 0.85])
    centers = np.stack([distances * np.cos(bearings), distances * np.sin(bearings)], axis=1)
    world = PlanarArmWorld(np.full(7, 1.0 / 7), centers, np.full(8, 0.12))
    space = ConfigurationSpace(np.r_[-np.pi, np.full(6, -2.6)], np.r_[np.pi, np.full(6, 2.6)])
    return _sample_queries("arm", space, world, count, rng)


def joint_space_obstacle_queries(count: int, seed: int) -> list[MotionQuery]:
    """Seven joints in [-pi, pi] among eight balls and ten slabs (boxes bounding two joints)."""
    rng = np.random.default_rng(seed)
    dimension, slab_count = 7, 10
    space = ConfigurationSpace(np.full(dimension, -np.pi), np.full(dimension, np.pi))
    lower = np.tile(space.lower, (slab_count, 1))
    upper = np.tile(space.upper, (slab_count, 1))
    for slab in range(slab_count):
        joints = rng.choice(dimension, size=2, replace=False)
        lower[slab, joints] = rng.uniform(-np.pi, np.pi - 1.0, size=2)
        upper[slab, joints] = lower[slab, joints] + rng.uniform(1.0, 2.0, size=2)
    world = JointSpaceObstacleWorld(
        rng.uniform(-2.0, 2.0, size=(8, dimension)),
        rng.uniform(2.0, 2.8, size=8),
        np.stack([lower, upper], axis=1),
    )
    return _sample_queries("joints", space, world, count, rng)


KITCHEN_PROBLEMS = tuple(
    Path(__file__).resolve().parents[1] / "pddl" / f for f in ("problem.pddl", "problem_hard.pddl")
)
JUDGE_AGREEMENT_MARGIN = 0.002
"""Clearance (m) our Drake and sphere checkers keep so that their paths pass PyBullet's check (which
pads each mesh by about 1 mm; see `kitchen_tamp.motion.geometry.drake`)."""
CHECKER_BACKENDS = ("pybullet", "drake", "spheres", "spheres-only")
"""spheres: the sphere model with Drake deciding what it rejects (as ``--collision-model spheres``
plans); spheres-only: the sphere model alone (conservative, so it rejects near-contact starts)."""


def _kitchen_walk(problem: Path, seed: Sequence[int], backend: str) -> list[MotionQuery]:
    """One free-space query per action of the problem's BFS plan, until a skill fails to sample."""
    from kitchen_tamp.kitchen import SkillFailure, load_kitchen_problem, sample_action_targets
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
    from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
    from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker
    from kitchen_tamp.planning.search.registry import plan
    from kitchen_tamp.world.scene_description import describe_collision_checker

    task, kitchen = load_kitchen_problem(problem)
    found = plan(task, "bfs")
    if found.plan is None:
        raise RuntimeError(f"{problem.name}: no symbolic plan ({found.status})")
    space = ConfigurationSpace(kitchen.robot.lower, kitchen.robot.upper)
    rng = np.random.default_rng(seed)
    queries: list[MotionQuery] = []
    for step, action in enumerate(found.plan):
        try:
            targets = sample_action_targets(kitchen, action, rng)
        except SkillFailure:
            break
        checker: CollisionChecker = targets.free_space_checker
        if backend == "drake":
            description = describe_collision_checker(targets.free_space_checker)
            checker = DrakeCollisionChecker(description, margin=JUDGE_AGREEMENT_MARGIN)
        if backend.startswith("spheres"):
            description = describe_collision_checker(targets.free_space_checker)
            checker = spheres = SphereCollisionChecker(description, margin=JUDGE_AGREEMENT_MARGIN)
            if backend == "spheres":
                drake = DrakeCollisionChecker(description, margin=JUDGE_AGREEMENT_MARGIN)
                checker = SphereScreenedChecker(spheres, drake, exact_is_bare=True)
        name = f"{problem.stem}-s{'.'.join(map(str, seed))}-{step}{targets.action_text}"
        queries.append(
            MotionQuery(
                name,
                kitchen.arm_configuration(),
                targets.goal_configuration,
                space,
                checker,
                targets.free_space_checker,
            )
        )
        targets.apply(kitchen)
    return queries


def kitchen_queries(count: int, seed: int, backend: str = "pybullet") -> list[MotionQuery]:
    """The kitchen task's free-space motions: the BFS plans of problem.pddl and
    problem_hard.pddl are walked action by action, again and again with samples
    seeded by (seed, walk, problem); each query goes from where the arm is to the
    skill's sampled goal configuration, checked by the skill's free-space checker
    or (``backend="drake"``) its Drake model."""
    if backend not in CHECKER_BACKENDS:
        raise ValueError(f"unknown checker backend {backend!r}; choose from {', '.join(CHECKER_BACKENDS)}")
    queries: list[MotionQuery] = []
    for walk in itertools.islice(itertools.count(), 100):
        for index, problem in enumerate(KITCHEN_PROBLEMS):
            queries += _kitchen_walk(problem, (seed, walk, index), backend)[: count - len(queries)]
            if len(queries) == count:
                return queries
    raise RuntimeError(f"only {len(queries)} kitchen queries could be sampled")


QUERY_SETS: dict[str, Callable[[int, int], list[MotionQuery]]] = {
    "planar_arm": planar_arm_queries,
    "joint_space_obstacles": joint_space_obstacle_queries,
    "kitchen": kitchen_queries,
}
"""Query-set name -> (count, seed) -> queries."""


@dataclass(frozen=True)
class Run:
    """One planner on one query: planning, then smoothing, each timed in CPU seconds."""

    solved: bool
    solve_cpu_s: float
    smooth_cpu_s: float
    path_length: float
    collision_checks: int

    @property
    def total_cpu_s(self) -> float:
        return self.solve_cpu_s + self.smooth_cpu_s


@dataclass(frozen=True, eq=False)
class Planned:
    """What a planner returned (a path or None) and what it cost: CPU seconds of planning and of
    smoothing, and configurations checked."""

    path: FloatArray | None
    solve_cpu_s: float
    smooth_cpu_s: float
    collision_checks: int


def judged(planned: Planned, query: MotionQuery, judge: CollisionChecker, resolution: float) -> Run:
    """The run, solved only if the path joins start and goal and ``judge`` finds it free at
    configurations ``resolution`` apart."""
    path, checks = planned.path, planned.collision_checks
    solve_s, smooth_s = planned.solve_cpu_s, planned.smooth_cpu_s
    if path is None:
        return Run(False, solve_s, smooth_s, float("nan"), checks)
    joins = np.allclose(path[0], query.start) and np.allclose(path[-1], query.goal)
    free = bool(np.all(judge.is_valid(densify_path(path, resolution))))
    return Run(joins and free, solve_s, smooth_s, path_length(path), checks)


def plan_ours(
    query: MotionQuery,
    checker: CollisionChecker,
    seed: int,
    time_budget_s: float,
    cpu_budget: bool = False,
    search: RrtConnectHyperparameters | None = None,
) -> Planned:
    """Our RRT-Connect (its step and iteration limit from ``search``, default the planner's own),
    then our shortcut with what is left of the budget (wall seconds, or with ``cpu_budget`` CPU
    seconds)."""
    clock = time.process_time if cpu_budget else time.perf_counter
    search = search or RrtConnectHyperparameters()
    cpu = time.process_time()
    planned = plan_rrt_connect(
        query.start,
        query.goal,
        query.space,
        checker,
        replace(search, edge_resolution=EDGE_RESOLUTION, clock=clock),
        seed=seed,
        time_budget_s=time_budget_s,
    )
    solve_s, cpu = time.process_time() - cpu, time.process_time()
    path, checks = planned.path, planned.collision_checks
    if path is not None:
        smoothed = shortcut_path(
            path,
            checker,
            ShortcutHyperparameters(edge_resolution=EDGE_RESOLUTION, clock=clock),
            seed=seed,
            time_budget_s=max(time_budget_s - planned.planning_time_s, 1e-3),
        )
        path, checks = smoothed.path, checks + smoothed.collision_checks
    return Planned(path, solve_s, time.process_time() - cpu, checks)


def plan_ompl(
    query: MotionQuery, checker: CollisionChecker, time_budget_s: float, cpu_budget: bool = False
) -> Planned:
    """OMPL's RRTConnect through SimpleSetup, then simplifySolution() with what is left of the
    budget (the same simplification as the unlimited default unless time runs out; wall seconds,
    or with ``cpu_budget`` CPU seconds, through a termination condition); ``checker`` is asked one
    configuration at a time, as OMPL's state validity checker."""
    from ompl import base as ob
    from ompl import geometric as og

    dimension = query.space.dimension
    state_space = ob.RealVectorStateSpace(dimension)
    bounds = ob.RealVectorBounds(dimension)
    for joint in range(dimension):
        bounds.setLow(joint, float(query.space.lower[joint]))
        bounds.setHigh(joint, float(query.space.upper[joint]))
    state_space.setBounds(bounds)
    setup = og.SimpleSetup(state_space)
    checks = 0

    def is_state_valid(state: object) -> bool:
        nonlocal checks
        checks += 1
        q = np.array([state[joint] for joint in range(dimension)])  # type: ignore[index]
        return bool(checker.is_valid(q[np.newaxis])[0])

    setup.setStateValidityChecker(is_state_valid)
    information = setup.getSpaceInformation()
    information.setStateValidityCheckingResolution(EDGE_RESOLUTION / state_space.getMaximumExtent())
    setup.setPlanner(og.RRTConnect(information))
    start, goal = state_space.allocState(), state_space.allocState()
    for joint in range(dimension):
        start[joint], goal[joint] = float(query.start[joint]), float(query.goal[joint])
    setup.setStartAndGoalStates(start, goal)
    setup.setup()

    cpu = time.process_time()
    if cpu_budget:
        deadline = cpu + time_budget_s
        setup.solve(ob.PlannerTerminationCondition(lambda: time.process_time() >= deadline))
    else:
        setup.solve(time_budget_s)
    solve_s, cpu = time.process_time() - cpu, time.process_time()
    path: FloatArray | None = None
    if setup.haveExactSolutionPath():
        if cpu_budget:
            deadline = max(deadline, cpu + 1e-3)
            setup.simplifySolution(ob.PlannerTerminationCondition(lambda: time.process_time() >= deadline))
        else:
            setup.simplifySolution(max(time_budget_s - setup.getLastPlanComputationTime(), 1e-3))
        solution = setup.getSolutionPath()
        path = np.array(
            [[solution.getState(i)[j] for j in range(dimension)] for i in range(solution.getStateCount())]
        )
    return Planned(path, solve_s, time.process_time() - cpu, checks)


def run_ours(query: MotionQuery, seed: int, time_budget_s: float) -> Run:
    """Our planner with the query's checker, judged by its judging checker."""
    planned = plan_ours(query, query.checker, seed, time_budget_s)
    return judged(planned, query, query.judging_checker, EDGE_RESOLUTION)


def run_ompl(query: MotionQuery, seed: int, time_budget_s: float) -> Run:
    """OMPL with the query's judging checker, judged by it."""
    planned = plan_ompl(query, query.judging_checker, time_budget_s)
    return judged(planned, query, query.judging_checker, EDGE_RESOLUTION)


RUNNERS: dict[str, Callable[[MotionQuery, int, float], Run]] = {
    "ours RRT-Connect+shortcut": run_ours,
    "OMPL RRTConnect+simplify": run_ompl,
}


@dataclass(frozen=True)
class Summary:
    """One planner over the queries: success over all queries; medians over the queries every
    planner solved (each column its own median, so total need not be solve + smooth); checks
    per CPU second over all queries."""

    planner: str
    success_rate: float
    median_solve_s: float
    median_smooth_s: float
    median_total_s: float
    median_path_length: float
    median_checks: float
    checks_per_second: float


def summarise(planner: str, runs: Sequence[Run], compared: Sequence[int]) -> Summary:
    """``compared``: indices of the queries every planner solved (all queries when there are none)."""
    solved = [runs[i] for i in compared] or list(runs)
    return Summary(
        planner=planner,
        success_rate=sum(run.solved for run in runs) / len(runs),
        median_solve_s=statistics.median(run.solve_cpu_s for run in solved),
        median_smooth_s=statistics.median(run.smooth_cpu_s for run in solved),
        median_total_s=statistics.median(run.total_cpu_s for run in solved),
        median_path_length=statistics.median(run.path_length for run in solved),
        median_checks=statistics.median(run.collision_checks for run in solved),
        checks_per_second=sum(r.collision_checks for r in runs) / sum(r.total_cpu_s for r in runs),
    )


def format_table(summaries: Sequence[Summary]) -> str:
    header = (
        f"{'planner (CPU s, medians)':<27}{'success':>8}{'solve':>9}{'smooth':>9}{'total':>9}"
        f"{'length':>8}{'checks':>8}{'checks/s':>10}"
    )
    rows = [
        f"{s.planner:<27}{s.success_rate:>8.0%}{s.median_solve_s:>9.4f}{s.median_smooth_s:>9.4f}"
        f"{s.median_total_s:>9.4f}{s.median_path_length:>8.3f}{s.median_checks:>8.0f}{s.checks_per_second:>10.0f}"
        for s in summaries
    ]
    return "\n".join([header, "-" * len(header), *rows])


def _ratio(ours: float, theirs: float) -> str:
    return f"{ours / theirs:.2f}x" if theirs > 0.0 else "n/a"


def format_comparison(ours: Summary, theirs: Summary) -> str:
    """Ratios ours/OMPL, then the project's bar: solve time no worse, success equal or better,
    length no longer (and, for smoothing's sake, total time no worse)."""
    ratios = {
        "solve": (ours.median_solve_s, theirs.median_solve_s),
        "smooth": (ours.median_smooth_s, theirs.median_smooth_s),
        "total": (ours.median_total_s, theirs.median_total_s),
        "length": (ours.median_path_length, theirs.median_path_length),
        "checks/s": (ours.checks_per_second, theirs.checks_per_second),
    }
    verdicts = {
        "solve time": ours.median_solve_s <= theirs.median_solve_s,
        "success": ours.success_rate >= theirs.success_rate,
        "length": ours.median_path_length <= theirs.median_path_length,
        "total time": ours.median_total_s <= theirs.median_total_s,
        "total 30x faster": 30.0 * ours.median_total_s <= theirs.median_total_s,
    }
    return "\n".join(
        [
            "ours/OMPL: " + ", ".join(f"{name} {_ratio(*pair)}" for name, pair in ratios.items()),
            "bar: " + ", ".join(f"{name} {'met' if met else 'MISSED'}" for name, met in verdicts.items()),
        ]
    )


BATCH_SIZE = 4096


def format_batch_throughput(queries: Sequence[MotionQuery], seed: int) -> str:
    """Configurations per CPU second of our checker (the sphere model alone when it screens for
    another) and the judge's, in batches of BATCH_SIZE uniform samples of the first four queries' scenes."""
    rng = np.random.default_rng(seed)
    ours_checked = judge_checked = 0
    ours_s = judge_s = 0.0
    for query in queries[:4]:
        qs = query.space.sample_uniform(rng, BATCH_SIZE)
        checker = getattr(query.checker, "spheres", query.checker)
        checker.is_valid(qs[:2])  # compile or warm up outside the clock
        cpu = time.process_time()
        checker.is_valid(qs)
        ours_s += time.process_time() - cpu
        ours_checked += len(qs)
        if query.judge is not None:
            cpu = time.process_time()
            query.judge.is_valid(qs[:512])
            judge_s += time.process_time() - cpu
            judge_checked += 512
    line = f"batch checks: ours {ours_checked / ours_s:,.0f}/CPU s (bar 1,000,000)"
    if judge_checked:
        judge_rate = judge_checked / judge_s
        line += f", PyBullet {judge_rate:,.0f}/CPU s, ratio {ours_checked / ours_s / judge_rate:.1f}x"
    return line


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--query-set", choices=[*sorted(QUERY_SETS), "mbm"], default="planar_arm")
    parser.add_argument("--queries", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--time-budget", type=float, help="seconds per query, plan + smooth (default 10; mbm: 1)"
    )
    parser.add_argument(
        "--checker", choices=CHECKER_BACKENDS, default="pybullet", help="collision model of the kitchen set"
    )
    parser.add_argument(
        "--scenarios", nargs="+", choices=MBM_SCENARIOS, default=list(MBM_SCENARIOS), help="mbm scenarios"
    )
    parser.add_argument("--problems", type=int, default=100, help="mbm problems per scenario (at most 100)")
    parser.add_argument("--save", type=Path, help="mbm: also write the runs to this JSON file")
    parser.add_argument("--from-saved", type=Path, nargs="+", help="mbm: print one table of saved runs")
    args = parser.parse_args(argv)
    if args.checker != "pybullet" and args.query_set != "kitchen":
        parser.error("--checker applies to the kitchen query set only")
    if args.query_set == "mbm":
        from mbm_motion import run_mbm, table_from_saved

        if not 1 <= args.problems <= 100:
            parser.error("--problems must be between 1 and 100")
        if args.from_saved:
            return table_from_saved(args.from_saved, args.time_budget or 1.0)
        return run_mbm(args.scenarios, args.problems, args.seed, args.time_budget or 1.0, args.save)
    args.time_budget = args.time_budget or 10.0

    from ompl import util as ou

    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    ou.RNG.setSeed(args.seed + 1)  # OMPL: one process-wide seed, set before any planner
    if args.query_set == "kitchen":
        queries = kitchen_queries(args.queries, args.seed, args.checker)
    else:
        queries = QUERY_SETS[args.query_set](args.queries, args.seed)
    runs: dict[str, list[Run]] = {name: [] for name in RUNNERS}
    for index, query in enumerate(queries):
        for name, runner in RUNNERS.items():
            runs[name].append(runner(query, args.seed + index, args.time_budget))
    both = [i for i in range(len(queries)) if all(planner_runs[i].solved for planner_runs in runs.values())]
    ours, theirs = (summarise(name, planner_runs, both) for name, planner_runs in runs.items())
    checker = f" ({args.checker} checker)" if args.query_set == "kitchen" else ""
    if args.query_set == "kitchen" and args.checker != "pybullet":
        checker = f" (ours: {args.checker} checker, OMPL: PyBullet checker)"
    print(
        f"{len(queries)} {args.query_set}{checker} queries, resolution {EDGE_RESOLUTION} rad, "
        f"budget {args.time_budget} s, seed {args.seed}; medians over the {len(both)} queries both solved"
    )
    if args.query_set == "kitchen":
        print(format_batch_throughput(queries, args.seed))
    print(format_table([ours, theirs]))
    print(format_comparison(ours, theirs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
