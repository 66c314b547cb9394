"""``final_project.py``: plan the kitchen task symbolically, refine every action into Panda
motion, replay it headless, verify it and write report.json, trajectory.json, replay.gif
and joints.png; ``replay RUN_DIR`` re-verifies and re-renders a saved run."""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from kitchen_tamp.bilevel import SampleEvent
from kitchen_tamp.cli import ExitCode, exit_code_of
from kitchen_tamp.cli.output_paths import OutputPathError, check_output_folder
from kitchen_tamp.execute import (
    FRAME_SECONDS,
    REPORT_FILE,
    TRAJECTORY_FILE,
    RunReport,
    SavedRun,
    Timeline,
    TrajectoryFileError,
    build_timeline,
    judge_under_physics,
    plot_joints,
    read_trajectory,
    render_replay,
    verify_trajectory,
    write_gif,
    write_trajectory,
)
from kitchen_tamp.execute.physics.replanning import Replanner
from kitchen_tamp.execute.render.browser_replay import (
    HTML_FILE,
    LiveViewer,
    RolloutRecorder,
    write_timeline_replay,
)
from kitchen_tamp.kitchen import KitchenError, KitchenMap, KitchenScene, build_kitchen_for_task
from kitchen_tamp.kitchen.scene.choice import choose_scene
from kitchen_tamp.motion import MOTION_PLANNERS, planner_options
from kitchen_tamp.motion.trajopt.solver import NoNonlinearSolverError, nonlinear_solver
from kitchen_tamp.planning import GroundAction, PlanningInputError, State, Task, load_task, plan
from kitchen_tamp.refinement import ActionSampleRecord, MotionBackend, SamplingMotionBackend
from kitchen_tamp.refinement.kitchen_sesame import (
    KITCHEN_BUDGETS,
    SesameRefinement,
    refine_with_sesame,
    sesame_replanner,
)
from kitchen_tamp.refinement.optimizing_backend import DEFAULT_SETTINGS, OptimizingMotionBackend
from kitchen_tamp.refinement.planning_checkers import COLLISION_MODELS, DEFAULT_COLLISION_MODEL
from kitchen_tamp.shipped_kitchens import DEFAULT_PROBLEM
from kitchen_tamp.world import UnknownNameError, WorldError

SYMBOLIC_PLANNER = "bfs"
"""Search that gives the symbolic plan: breadth-first, so the plan is shortest."""
SYMBOLIC_TIME_BUDGET_S = 60.0
GIF_FILE = "replay.gif"
JOINTS_FILE = "joints.png"


class UsageError(Exception):
    """A command line that cannot run as asked (exit 2)."""


BAD_INPUT_ERRORS = (UsageError, OutputPathError, PlanningInputError, KitchenError, TrajectoryFileError)
"""Errors in what the user gave (options, files, output folder): one line, exit 2."""


def _integer_at_least(minimum: int) -> Callable[[str], int]:
    """An argparse type: an integer no smaller than ``minimum``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be at least {minimum}, got {value}")
        return value

    return parse


def _add_viewing_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--scene", type=Path, metavar="FILE",
                        help="kitchen scene file (default: scene.toml beside the problem, else the "
                             "default kitchen; replay: the scene the run recorded)")
    parser.add_argument("--out", type=Path, metavar="DIR", help="output folder")
    parser.add_argument("--no-video", action="store_true", help="do not render replay.gif and replay.html")
    parser.add_argument("--meshcat", action="store_true",
                        help="serve a live 3D viewer (Meshcat) on this machine while the program runs")
    parser.add_argument("--gui", action="store_true", help="also play the run in a PyBullet window")
    parser.add_argument("--step", action="store_true", help="wait for Enter before each action of the replay")
    parser.add_argument("--no-physics", action="store_true", help="skip execution under physics")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="final_project.py",
        description="Kitchen task-and-motion planning for a Franka Panda: symbolic plan, skills, "
                    "motion planning per step, headless replay, verification.")
    modes = parser.add_subparsers(dest="mode", required=True, metavar="MODE")
    helps = {
        "rrt": "solve each step with a joint-space RRT (RRT-Connect by default) and shortcutting",
        "optimizes": "solve each step with Drake trajectory optimisation",
    }
    for mode, text in helps.items():
        sub = modes.add_parser(mode, help=text, description=text)
        sub.add_argument("--problem", default=DEFAULT_PROBLEM,
                         help="problem file; a bare name is looked up in the working directory, beside "
                              "the scene file, then in the shipped kitchens (default: %(default)s)")
        sub.add_argument("--domain", help="domain file (default: domain.pddl beside the problem, else "
                                          "the shipped kitchen domain)")
        sub.add_argument("--seed", type=_integer_at_least(0), default=0, help="random seed (default 0)")
        sub.add_argument("--max-plans", type=_integer_at_least(1), default=KITCHEN_BUDGETS.max_plans,
                         metavar="N",
                         help="abstract plans SeSamE may try, shortest first (default %(default)s)")
        sub.add_argument("--samples-per-step", type=_integer_at_least(1),
                         default=KITCHEN_BUDGETS.samples_per_step, metavar="N",
                         help="samples of an action (targets + motion) before SeSamE "
                              "steps back (default %(default)s)")
        sub.add_argument("--max-samples", type=_integer_at_least(1), default=KITCHEN_BUDGETS.max_samples,
                         metavar="N", help="samples over the whole run (default %(default)s)")
        sub.add_argument(
            "--collision-model", choices=sorted(COLLISION_MODELS), default=DEFAULT_COLLISION_MODEL,
            help="collision model for planning (default %(default)s; PyBullet always verifies)",
        )
        if mode == "optimizes":
            sub.add_argument("--waypoints", type=_integer_at_least(2), default=DEFAULT_SETTINGS.num_waypoints,
                             metavar="N", help="joint waypoints per move (default %(default)s)")
        if mode == "rrt":
            options = planner_options()
            sub.add_argument("--rrt", choices=list(options), default=next(iter(options)),
                             help="; ".join(f"{option}: {MOTION_PLANNERS[name].summary}"
                                            for option, name in options.items()) + " (default %(default)s)")
        _add_viewing_options(sub)
    replay = modes.add_parser("replay", help="re-verify and re-render a saved run without planning")
    replay.add_argument("run_dir", type=Path, metavar="RUN_DIR", help="folder with trajectory.json")
    _add_viewing_options(replay)
    return parser


def _say(text: str) -> None:
    print(text, flush=True)


def _check_display(args: argparse.Namespace) -> None:
    if args.gui and sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
        raise UsageError("--gui needs a display, and DISPLAY is not set (run without --gui: it is headless)")


def _motion_backend(args: argparse.Namespace) -> MotionBackend:
    if args.mode == "optimizes":
        if args.collision_model == "pybullet":
            raise UsageError("optimizes needs signed distances: use --collision-model spheres or drake")
        nonlinear_solver()  # raises NoNonlinearSolverError now rather than at the first optimised move
        return OptimizingMotionBackend(replace(DEFAULT_SETTINGS, num_waypoints=args.waypoints))
    return SamplingMotionBackend(planner=planner_options()[args.rrt])


def _physics_replanner(run: SavedRun) -> Replanner:
    """SeSamE with the run's motion back end (its defaults), for re-plans under physics."""
    if run.mode == "optimizes":
        return sesame_replanner(OptimizingMotionBackend(DEFAULT_SETTINGS), run.seed)
    return sesame_replanner(SamplingMotionBackend(), run.seed)


def _progress(event: SampleEvent[State, GroundAction], record: ActionSampleRecord | None) -> None:
    """One line per sample: which plan and step, and what the sample gave."""
    where = f"plan {(event.plan_index or 0) + 1}, step {(event.step_index or 0) + 1}"
    head = f"[{where}] {event.transition.action.text}"
    seconds = 0.0
    if record is not None:
        seconds = record.seconds.get("skills_s", 0.0) + record.seconds.get("motion_s", 0.0)
    if event.succeeded and record is not None:
        _say(f"{head}: {record.planner}, {record.waypoints} waypoints "
             f"({record.motion.get('waypoints')} planned), {seconds:.2f} s")
    else:
        _say(f"{head}: sample failed ({event.failure}), {seconds:.2f} s")


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


def _start_live_viewer(kitchen: KitchenScene) -> LiveViewer:
    live = LiveViewer(kitchen)
    _say(f"live viewer (Meshcat) at {live.url} while this program runs")
    return live


def _wait_for_enter(index: int, action: str) -> None:
    input(f"step {index + 1}: {action}  (press Enter)")


def _play_in_window(kitchen: KitchenScene, timeline: Timeline, step: bool) -> None:
    """Play the run at nominal speed in the GUI scene (waiting for Enter per action if asked)."""
    times = np.arange(0.0, timeline.duration, 1.0 / 30.0)
    current = -1
    for _, index in timeline.play(kitchen, times):
        if step and index != current:
            _wait_for_enter(index, timeline.actions[index])
        current = index
        time.sleep(1.0 / 30.0)


def verify_and_render(
    task: Task,
    run: SavedRun,
    out_dir: Path,
    report: RunReport,
    args: argparse.Namespace,
    kitchen_map: KitchenMap,
    report_name: str = REPORT_FILE,
    live: LiveViewer | None = None,
) -> int:
    """Verify ``run`` in a fresh kitchen, plot and render it, write the report; the exit code."""
    clock = time.perf_counter()
    trajectory = run.trajectory
    wait = _wait_for_enter if args.step and not args.gui else None
    with build_kitchen_for_task(task, gui=args.gui, kitchen_map=kitchen_map) as fresh:
        live = _start_live_viewer(fresh) if args.meshcat and live is None else live
        initial = fresh.scene.save_state()
        verification = verify_trajectory(fresh, task, trajectory, on_step=wait)
        timeline = build_timeline(trajectory, verification.tracks)
        if args.gui:
            fresh.scene.restore_state(initial)
            _play_in_window(fresh, timeline, args.step)
    report.verification = verification.report_data()
    if not verification.verified:
        report.fail("verification", "; ".join(verification.problems[:3]) or "verification failed")
    report.timing["verification_s"] = time.perf_counter() - clock
    rollout = None if args.no_video else RolloutRecorder()
    if not args.no_physics:
        judge_under_physics(task, trajectory, report, on_frame=rollout, replan=_physics_replanner(run),
                            kitchen_map=kitchen_map)
    clock = time.perf_counter()
    title = f"{run.problem.name}, {run.mode}, seed {run.seed}: joint angles"
    show_velocities = run.mode == "optimizes"
    if show_velocities:
        title = f"{run.problem.name}, {run.mode}, seed {run.seed}: joint angles and velocities"
    report.outputs["joints_plot"] = plot_joints(timeline, title, out_dir / JOINTS_FILE, show_velocities).name
    report.outputs["gif"] = report.outputs["html"] = None
    if not args.no_video:
        with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
            html_clock = time.perf_counter()
            if rollout is not None and rollout.captured:  # the motion the simulator executed
                report.outputs["html"] = rollout.write(out_dir / HTML_FILE, live).name
                report.outputs["html_shows"] = "physics"
            else:
                html = write_timeline_replay(kitchen, timeline, out_dir / HTML_FILE, live)
                report.outputs["html"] = html.name
                report.outputs["html_shows"] = "kinematic replay"
            report.timing["html_s"] = time.perf_counter() - html_clock
            images = render_replay(kitchen, timeline)
        report.outputs["gif"] = write_gif(out_dir / GIF_FILE, images, FRAME_SECONDS).name
        _say(f"rendered {len(images)} frames of the replay")
    report.timing["rendering_s"] = time.perf_counter() - clock
    return _finish(report, out_dir, report_name)


def _finish(report: RunReport, out_dir: Path, report_name: str = REPORT_FILE) -> int:
    if report.started is not None:
        report.timing["total_s"] = time.perf_counter() - report.started
    path = report.write(out_dir / report_name)
    verification = report.verification or {}
    if report.solved:
        goals = ", ".join(verification.get("goal_atoms", {}))  # type: ignore[arg-type]
        clearance = float(verification.get("min_clearance_m", 0.0))  # type: ignore[arg-type]
        _say(f"SOLVED and verified: {len(report.plan or [])} actions, collision-free "
             f"(min clearance {clearance * 1000:.1f} mm), goal {goals} true; {report.verdicts()}; "
             f"report {path}")
        return int(ExitCode.SOLVED)
    failure = report.failure or {}
    _say(f"NOT SOLVED ({failure.get('stage')}): {failure.get('reason')}; {report.verdicts()}; report {path}")
    return int(ExitCode.NO_PLAN)


def run_plan(args: argparse.Namespace, started: float) -> int:
    """``rrt`` / ``optimizes``: plan, refine, write the trajectory, verify and render."""
    _check_display(args)
    backend = _motion_backend(args)
    choice = choose_scene(args.problem, args.scene, Path(args.domain) if args.domain else None)
    problem, domain = choice.problem.absolute(), choice.domain.absolute()
    kitchen_map = choice.kitchen_map()
    out_dir: Path = args.out or Path("out") / f"{problem.stem}-{args.mode}-seed{args.seed}"
    check_output_folder(out_dir, "--out" if args.out else "output folder")
    task = load_task(problem, domain)
    report = RunReport(problem, domain, args.mode, backend.name, args.seed, SYMBOLIC_PLANNER)
    report.started = started
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        live = _start_live_viewer(kitchen) if args.meshcat else None

        def on_sample(event: SampleEvent[State, GroundAction], record: ActionSampleRecord | None) -> None:
            _progress(event, record)
            if live is not None:
                live.update()

        report.timing["startup_s"] = time.perf_counter() - started
        clock = time.perf_counter()
        result = plan(task, SYMBOLIC_PLANNER, time_budget=SYMBOLIC_TIME_BUDGET_S)
        report.timing["symbolic_s"] = time.perf_counter() - clock
        if result.plan is None:
            report.fail("symbolic", f"no symbolic plan: {result.message}")
            return _finish(report, out_dir)
        report.plan = [action.text for action in result.plan]
        _say(f"{problem.name}: shortest plan has {len(result.plan)} actions; refining with SeSamE and "
             f"{backend.name} (seed {args.seed})")
        clock = time.perf_counter()
        budgets = replace(KITCHEN_BUDGETS, max_plans=args.max_plans, samples_per_step=args.samples_per_step,
                          max_samples=args.max_samples)
        outcome = refine_with_sesame(
            kitchen, task, backend, args.seed, budgets, args.collision_model, on_sample=on_sample
        )
        report.timing["refinement_s"] = time.perf_counter() - clock
        report.bilevel = outcome.report_data()
        refined = outcome.refined
        if refined is None:
            step, action = _stuck_step(outcome)
            report.fail("refinement", f"SeSamE: {outcome.result.detail}", step, action)
            return _finish(report, out_dir)
        report.plan = refined.trajectory.plan
    report.steps = [r.figures() for r in refined.records]
    _record_step_timing(report, refined.records)
    run = SavedRun(problem, domain, args.mode, args.seed, refined.trajectory, scene=choice.scene.absolute())
    report.outputs["trajectory"] = write_trajectory(out_dir / TRAJECTORY_FILE, run).name
    return verify_and_render(task, run, out_dir, report, args, kitchen_map, live=live)


def _record_step_timing(report: RunReport, records: Sequence[ActionSampleRecord]) -> None:
    report.timing["skills_s"] = sum(r.seconds.get("skills_s", 0.0) for r in records)
    report.timing["motion_s"] = sum(r.seconds.get("motion_s", 0.0) for r in records)
    report.timing["steps"] = [
        {"action": r.action, **{k: round(v, 4) for k, v in r.seconds.items()}} for r in records
    ]


def run_replay(args: argparse.Namespace, started: float) -> int:
    """``replay RUN_DIR``: verify and render a saved trajectory again, without planning."""
    _check_display(args)
    out_dir: Path = args.out or args.run_dir
    check_output_folder(out_dir, "--out" if args.out else "RUN_DIR")
    run = read_trajectory(args.run_dir / TRAJECTORY_FILE)
    if run.ignored_fields:
        _say(f"note: not reading {', '.join(run.ignored_fields)} from the trajectory file: the judge "
             "derives them from the kitchen")
    task = load_task(run.problem, run.domain)
    kitchen_map = choose_scene(run.problem, _replay_scene(args.scene, run), run.domain).kitchen_map()
    report = RunReport(run.problem, run.domain, run.mode, "replay", run.seed, SYMBOLIC_PLANNER)
    report.plan = run.trajectory.plan
    report.started = started
    _say(f"replaying {len(run.trajectory.steps)} actions of {args.run_dir} ({run.problem.name}, {run.mode}, "
         f"seed {run.seed})")
    report.outputs["trajectory"] = str(args.run_dir / TRAJECTORY_FILE)
    return verify_and_render(task, run, out_dir, report, args, kitchen_map, report_name="replay_report.json")


def _replay_scene(given: Path | None, run: SavedRun) -> Path | None:
    """The kitchen to judge a saved run in: ``--scene`` if given, else the scene file the run
    recorded (older files record none: the one beside the problem, else the default)."""
    if given is not None or run.scene is None:
        return given
    if not run.scene.is_file():
        raise TrajectoryFileError(f"{run.scene}: the scene file this run planned in is gone; "
                                  "pass --scene FILE to judge it in another kitchen")
    return run.scene


def _bad_input_line(error: Exception) -> str | None:
    """The one line for an error in the user's input or setup (exit 2); ``None`` for a bug."""
    if isinstance(error, BAD_INPUT_ERRORS):
        return str(error)
    if isinstance(error, NoNonlinearSolverError):
        return f"optimizes needs a nonlinear solver: {error}; use rrt, or a Drake build that has one"
    if isinstance(error, UnknownNameError):
        return f"the kitchen's model files do not match its kitchen map: {error}"
    if isinstance(error, WorldError):
        return f"the kitchen could not be set up: {error}"
    return None


def main(argv: Sequence[str] | None = None, started: float | None = None) -> int:
    """Run the command line; returns the exit code (see ``ExitCode``)."""
    run_started = time.perf_counter() if started is None else started
    args = build_parser().parse_args(argv)
    if args.mode == "replay":
        return exit_code_of(lambda: run_replay(args, run_started), _bad_input_line)
    return exit_code_of(lambda: run_plan(args, run_started), _bad_input_line)


if __name__ == "__main__":  # python -m kitchen_tamp.cli.final_project (how sweeps run it)
    sys.exit(main())
