"""``final_project.py``: plan the kitchen task symbolically, refine every action into Panda
motion, replay it headless, verify it and write report.json, trajectory.json, replay.gif
and joints.png; ``replay RUN_DIR`` judges and renders a saved run again, without planning."""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import NoReturn

from kitchen_tamp.bilevel import SampleEvent
from kitchen_tamp.bilevel.relational import LARGE_TASK_SEARCH, SHORTEST_FIRST_MAX_ACTIONS
from kitchen_tamp.cli import exit_code_of
from kitchen_tamp.cli.final_project_parser import build_parser
from kitchen_tamp.cli.output_paths import OutputPathError, prepare_output_folder
from kitchen_tamp.cli.run_clock import exit_now, process_start
from kitchen_tamp.cli.run_judging import (
    RunContext,
    ViewingOptions,
    finish,
    following_judge,
    judge_and_render,
    say,
    start_live_viewer,
)
from kitchen_tamp.cli.run_profile import PROFILE_OPTION, profile_if_asked
from kitchen_tamp.execute import TRAJECTORY_FILE, RunReport, SavedRun, TrajectoryFileError, read_trajectory
from kitchen_tamp.execute import write_trajectory as write_trajectory_file
from kitchen_tamp.execute.following_judge import FollowingJudge
from kitchen_tamp.execute.physics.replanning import Replanner
from kitchen_tamp.execute.run_inputs import RunInputs
from kitchen_tamp.kitchen import KitchenError, build_kitchen_for_task
from kitchen_tamp.kitchen.scene.choice import SceneChoice, choose_scene
from kitchen_tamp.motion import planner_options
from kitchen_tamp.motion.geometry.drake_service import DrakeService
from kitchen_tamp.planning import GroundAction, PlanningInputError, State, Task, load_task, plan
from kitchen_tamp.refinement import ActionSampleRecord, MotionBackend, SamplingMotionBackend
from kitchen_tamp.refinement.kitchen_sesame import (
    KITCHEN_BUDGETS,
    RefinementOptions,
    SesameRefinement,
    refine_with_sesame,
    sesame_replanner,
)
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from kitchen_tamp.world import UnknownNameError, WorldError

SYMBOLIC_PLANNER = "bfs"
"""Search that gives the symbolic plan: breadth-first, so the plan is shortest."""
SYMBOLIC_TIME_BUDGET_S = 60.0
REPLAY_REPORT_FILE = "replay_report.json"


class UsageError(Exception):
    """A command line that cannot run as asked (exit 2)."""


BAD_INPUT_ERRORS = (UsageError, OutputPathError, PlanningInputError, KitchenError, TrajectoryFileError)
"""Errors in what the user gave (options, files, output folder): one line, exit 2."""


def symbolic_planner(task: Task) -> str:
    """Breadth-first search (a shortest plan), or greedy best-first on a large task, where
    SeSamE's abstract plans too come best first rather than shortest first."""
    return SYMBOLIC_PLANNER if len(task.actions) <= SHORTEST_FIRST_MAX_ACTIONS else LARGE_TASK_SEARCH


def _check_display(args: argparse.Namespace) -> None:
    if args.gui and sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
        raise UsageError("--gui needs a display, and DISPLAY is not set (run without --gui: it is headless)")


def _viewing(args: argparse.Namespace) -> ViewingOptions:
    return ViewingOptions(args.gui, args.step, args.meshcat, not args.no_video, not args.no_physics)


def _motion_backend(args: argparse.Namespace) -> MotionBackend:
    if args.mode == "optimizes":
        if args.collision_model == "pybullet":
            raise UsageError("optimizes needs signed distances: use --collision-model spheres or drake")
        from kitchen_tamp.motion.trajopt import solver  # Drake: loaded by a run that optimises
        from kitchen_tamp.refinement.optimizing_backend import OptimizingMotionBackend

        try:
            solver.nonlinear_solver()  # now rather than at the first optimised move
        except solver.NoNonlinearSolverError as error:
            raise UsageError(f"optimizes needs a nonlinear solver: {error}; use rrt, or a Drake build "
                             "that has one") from error
        return OptimizingMotionBackend(replace(DEFAULT_SETTINGS, num_waypoints=args.waypoints))
    return SamplingMotionBackend(planner=planner_options()[args.rrt])


def _physics_replanner(mode: str, seed: int) -> Replanner:
    """SeSamE with the run's motion back end (its defaults), for re-plans under physics."""
    if mode == "optimizes":
        from kitchen_tamp.refinement.optimizing_backend import OptimizingMotionBackend

        return sesame_replanner(OptimizingMotionBackend(DEFAULT_SETTINGS), seed)
    return sesame_replanner(SamplingMotionBackend(), seed)


class _Progress:
    """One line per sample (which plan and step, what the sample gave), counting failures."""

    def __init__(self) -> None:
        self.failures: Counter[str] = Counter()

    def __call__(self, event: SampleEvent[State, GroundAction], record: ActionSampleRecord | None) -> None:
        where = f"plan {(event.plan_index or 0) + 1}, step {(event.step_index or 0) + 1}"
        head = f"[{where}] {event.transition.action.text}"
        seconds = 0.0
        if record is not None:
            seconds = record.seconds.get("skills_s", 0.0) + record.seconds.get("motion_s", 0.0)
        if event.succeeded and record is not None:
            say(f"{head}: {record.planner}, {record.waypoints} waypoints "
                f"({record.motion.get('waypoints')} planned), {seconds:.2f} s")
        else:
            self.failures[f"{event.transition.action.text}: {event.failure}"] += 1
            say(f"{head}: sample failed ({event.failure}), {seconds:.2f} s")

    def most_frequent(self) -> str:
        """The failure that happened most, e.g. ``(placeIn ...): ... (7 of 12 failed samples)``."""
        if not self.failures:
            return ""
        text, count = self.failures.most_common(1)[0]
        return f"; most frequent failure ({count} of {sum(self.failures.values())} failed samples): {text}"


def _stuck_step(outcome: SesameRefinement) -> tuple[int | None, str | None]:
    """(1-based step, action) where the first abstract plan's refinement got stuck."""
    attempts = outcome.result.attempts
    if not attempts:
        return None, None
    failing = [step for step in attempts[0].steps if step.failures]
    if not failing:
        return None, None
    step = failing[-1]
    return step.index + 1, step.action.text


def run_plan(args: argparse.Namespace, started: float) -> int:
    """``rrt`` / ``optimizes``: plan, refine, write the trajectory, judge and render."""
    _check_display(args)
    backend = _motion_backend(args)
    # Drake behind the sphere model: loaded in a process of its own while the planner starts
    # (trajectory optimisation and the drake model use Drake in this process anyway)
    spheres_alone = args.mode == "rrt" and args.collision_model == "spheres"
    drake = DrakeService() if spheres_alone and DrakeService.available() else None
    try:
        return _plan_and_judge(args, started, backend, drake)
    finally:
        if drake is not None:
            drake.close()


def _plan_and_judge(
    args: argparse.Namespace, started: float, backend: MotionBackend, drake: DrakeService | None
) -> int:
    choice = choose_scene(args.problem, args.scene, Path(args.domain) if args.domain else None)
    problem, domain, scene = choice.problem.absolute(), choice.domain.absolute(), choice.scene.absolute()
    kitchen_map = choice.kitchen_map()
    out_dir: Path = args.out or Path("out") / f"{problem.stem}-{args.mode}-seed{args.seed}"
    task = load_task(problem, domain)
    prepare_output_folder(out_dir, "--out" if args.out else "output folder")
    inputs = RunInputs.of({"problem": problem, "domain": domain, "scene": scene})
    planner = symbolic_planner(task)
    report = RunReport(problem, domain, args.mode, backend.name, args.seed, planner, scene=scene)
    report.inputs, report.started = inputs.data(), started
    viewing, replan = _viewing(args), _physics_replanner(args.mode, args.seed)
    followed: FollowingJudge | None = None
    try:
        with build_kitchen_for_task(task, kitchen_map=kitchen_map, visuals=args.meshcat) as kitchen:
            # Forked once a kitchen is built, so that its children build theirs from PyBullet's
            # warm file cache; they get ready while the plan is found.
            followed = following_judge(task, kitchen_map, viewing, replan)
            live = start_live_viewer(kitchen) if args.meshcat else None
            progress = _Progress()

            def on_sample(event: SampleEvent[State, GroundAction], record: ActionSampleRecord | None) -> None:
                progress(event, record)
                if live is not None:
                    live.update()
                accepted = record.trajectory if record is not None and event.succeeded else None
                if followed is not None and accepted is not None and event.plan_index is not None:
                    assert event.step_index is not None
                    followed.accepted(event.plan_index, event.step_index, accepted)

            report.timing["startup_s"] = time.perf_counter() - started
            clock = time.perf_counter()
            result = plan(task, planner, time_budget=SYMBOLIC_TIME_BUDGET_S)
            report.timing["symbolic_s"] = time.perf_counter() - clock
            if result.plan is None:
                report.fail("symbolic", f"no symbolic plan: {result.message}")
                return _stopped(followed, report, out_dir, inputs)
            report.plan = [action.text for action in result.plan]
            which = "shortest plan" if planner == SYMBOLIC_PLANNER else f"{planner} plan"
            say(f"{problem.name}: {which} has {len(result.plan)} actions; refining with SeSamE and "
                f"{backend.name} (seed {args.seed})")
            clock = time.perf_counter()
            budgets = replace(KITCHEN_BUDGETS, max_plans=args.max_plans,
                              samples_per_step=args.samples_per_step, max_samples=args.max_samples)
            options = RefinementOptions(args.collision_model, feedback=not args.no_feedback, drake=drake)
            outcome = refine_with_sesame(kitchen, task, backend, args.seed, budgets, options, on_sample)
            report.timing["refinement_s"] = time.perf_counter() - clock
            report.bilevel = outcome.report_data()
            refined = outcome.refined
            if refined is None:
                step, action = _stuck_step(outcome)
                reason = f"SeSamE: {outcome.result.detail}{progress.most_frequent()}"
                report.fail("refinement", reason, step, action)
                return _stopped(followed, report, out_dir, inputs)
            report.plan = refined.trajectory.plan
        report.steps = [r.figures() for r in refined.records]
        _record_step_timing(report, refined.records)
        run = SavedRun(problem, domain, args.mode, args.seed, refined.trajectory, scene=scene,
                       sha256=inputs.digests())
        trajectory_file = write_trajectory_file(out_dir / TRAJECTORY_FILE, run)
    except BaseException:
        if followed is not None:
            followed.cancel()
        raise
    report.outputs["trajectory"] = trajectory_file.name
    context = RunContext(task, kitchen_map, run, trajectory_file, out_dir, report, inputs, viewing,
                         live=live, replan=replan, followed=followed)
    return judge_and_render(context)


def _stopped(followed: FollowingJudge | None, report: RunReport, out_dir: Path, inputs: RunInputs) -> int:
    """A run that wrote no trajectory: the judges that were to follow it stopped, the report written."""
    if followed is not None:
        followed.cancel()
    return finish(report, out_dir, inputs)


def _record_step_timing(report: RunReport, records: Sequence[ActionSampleRecord]) -> None:
    for part in ("skills_s", "checkers_s", "motion_s", "judge_replay_s"):  # of the accepted samples
        report.timing[part] = sum(r.seconds.get(part, 0.0) for r in records)
    report.timing["steps"] = [
        {"action": r.action, **{k: round(v, 4) for k, v in r.seconds.items()}} for r in records
    ]


def _replay_choice(args: argparse.Namespace, run: SavedRun) -> SceneChoice:
    """The files to judge a saved run against: those named on the command line, else the ones
    the run recorded (a file written before scenes were recorded: the scene beside the problem,
    else the default kitchen)."""
    if args.scene is None and run.scene is not None and not run.scene.is_file():
        raise TrajectoryFileError(f"{run.scene}: the scene file this run planned in is gone; "
                                  "pass --scene FILE to judge it in another kitchen")
    return choose_scene(args.problem or run.problem, args.scene or run.scene, args.domain or run.domain)


def run_replay(args: argparse.Namespace, started: float) -> int:
    """``replay RUN_DIR``: judge and render a saved trajectory again, without planning."""
    _check_display(args)
    out_dir: Path = args.out or args.run_dir
    trajectory_file = args.run_dir / TRAJECTORY_FILE
    if args.out is not None:
        prepare_output_folder(out_dir, "--out")
    run = read_trajectory(trajectory_file)  # before RUN_DIR is made ready: it must exist already
    prepare_output_folder(out_dir, "--out" if args.out else "RUN_DIR")
    if run.ignored_fields:
        say(f"note: not reading {', '.join(run.ignored_fields)} from the trajectory file: the judge "
            "derives them from the kitchen")
    choice = _replay_choice(args, run)
    inputs = RunInputs.of({"problem": choice.problem, "domain": choice.domain, "scene": choice.scene},
                          recorded=run.sha256)
    task = load_task(choice.problem, choice.domain)
    kitchen_map = choice.kitchen_map()
    report = RunReport(choice.problem, choice.domain, run.mode, "replay", run.seed, SYMBOLIC_PLANNER,
                       scene=choice.scene)
    report.plan, report.started, report.inputs = run.trajectory.plan, started, inputs.data()
    say(f"replaying {len(run.trajectory.steps)} actions of {args.run_dir} ({run.problem.name}, {run.mode}, "
        f"seed {run.seed}); {inputs.words()}")
    report.outputs["trajectory"] = str(trajectory_file)
    context = RunContext(task, kitchen_map, run, trajectory_file, out_dir, report, inputs, _viewing(args),
                         report_name=REPLAY_REPORT_FILE)
    return judge_and_render(context)


def _bad_input_line(error: Exception) -> str | None:
    """The one line for an error in the user's input or setup (exit 2); ``None`` for a bug."""
    if isinstance(error, BAD_INPUT_ERRORS):
        return str(error)
    if isinstance(error, UnknownNameError):
        return f"the kitchen's model files do not match its kitchen map: {error}"
    if isinstance(error, WorldError):
        return f"the kitchen could not be set up: {error}"
    return None


def main(argv: Sequence[str] | None = None, started: float | None = None) -> int:
    """Run the command line; returns the exit code (see ``ExitCode``). ``started`` is the
    ``time.perf_counter()`` reading the report's timing counts from (default: now)."""
    run_started = time.perf_counter() if started is None else started
    args = build_parser().parse_args(argv)
    if args.profile:
        profile_if_asked([PROFILE_OPTION])  # from here when the entry script has not started it
    if args.mode == "replay":
        return exit_code_of(lambda: run_replay(args, run_started), _bad_input_line)
    return exit_code_of(lambda: run_plan(args, run_started), _bad_input_line)


def run() -> NoReturn:
    """The ``kitchen-tamp`` command: ``main`` timed from the process's start, then a quick exit."""
    profile_if_asked(sys.argv)
    exit_now(main(started=process_start()))


if __name__ == "__main__":  # python -m kitchen_tamp.cli.final_project (how sweeps run it)
    run()
