"""What ``final_project.py`` does with a trajectory once it has one: both judges, the pictures,
the report and the verdict line -- the same for a planning run and for ``replay``.

The kinematic judge replays the file in a fresh kitchen; physics executes the file as
the kinematic judge read it. Neither plans. In a planning run (``RunContext.replan``
set), a scene that drifts under physics has the rest of the plan refined again from the
simulated scene; those steps are written into ``trajectory.json`` and the file is judged
again from the start, so the file holds exactly what was judged, and ``replay`` of it
gives the same verdict (at most ``MAX_REPLANS`` times).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Final

import numpy as np

from kitchen_tamp.cli import ExitCode
from kitchen_tamp.cli.run_profile import write_profile
from kitchen_tamp.execute import (
    REPORT_FILE,
    RunReport,
    SavedRun,
    Timeline,
    Verification,
    build_timeline,
    judged_pairs,
    verify_trajectory,
    write_trajectory,
)
from kitchen_tamp.execute.following_judge import FollowingJudge
from kitchen_tamp.execute.physics.background_physics import (
    PendingPhysics,
    PhysicsJob,
    PhysicsOutcome,
)
from kitchen_tamp.execute.physics.execution import report_seconds
from kitchen_tamp.execute.physics.replanning import Replanner
from kitchen_tamp.execute.render.background_pictures import PendingPictures, PictureJob
from kitchen_tamp.execute.render.rollout_recording import RecordedRollout
from kitchen_tamp.execute.run_inputs import RunInputs
from kitchen_tamp.execute.trajectory_file import check_joint_count
from kitchen_tamp.kitchen import KitchenMap, KitchenScene, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task

if TYPE_CHECKING:  # the browser's page loads Drake, which a run without it never needs
    from kitchen_tamp.execute.render.browser_replay import LiveViewer

MAX_REPLANS: Final = 2
"""Re-plans under physics a planning run may make before its verdict stands."""


def say(text: str) -> None:
    print(text, flush=True)


@dataclass(frozen=True)
class ViewingOptions:
    """What to show and what to skip (from the command line)."""

    gui: bool = False
    step: bool = False
    meshcat: bool = False
    video: bool = True
    physics: bool = True


@dataclass
class RunContext:
    """A run to judge and picture: the task and its kitchen, the saved run, where its outputs
    go, and (in a planning run) how to re-plan under physics and where the file lives."""

    task: Task
    kitchen_map: KitchenMap
    run: SavedRun
    trajectory_file: Path
    """The file the run is read from (a planning run writes its re-plans there)."""
    out_dir: Path
    report: RunReport
    inputs: RunInputs
    viewing: ViewingOptions
    report_name: str = REPORT_FILE
    live: LiveViewer | None = None
    replan: Replanner | None = None
    """How a planning run re-plans under physics (None in a replay: it never re-plans)."""
    replans: list[dict[str, object]] = field(default_factory=list)
    followed: FollowingJudge | None = None
    """The judges that followed the planning run's steps as it accepted them, if any."""


def start_live_viewer(kitchen: KitchenScene) -> LiveViewer:
    from kitchen_tamp.execute.render.browser_replay import LiveViewer  # Drake: only where it is seen

    live = LiveViewer(kitchen)
    say(f"live viewer (Meshcat) at {live.url} while this program runs")
    return live


def wait_for_enter(index: int, action: str) -> None:
    input(f"step {index + 1}: {action}  (press Enter)")


def _play_in_window(kitchen: KitchenScene, timeline: Timeline, step: bool) -> None:
    """Play the run at nominal speed in the GUI scene (waiting for Enter per action if asked)."""
    times = np.arange(0.0, timeline.duration, 1.0 / 30.0)
    current = -1
    for _, index in timeline.play(kitchen, times):
        if step and index != current:
            wait_for_enter(index, timeline.actions[index])
        current = index
        time.sleep(1.0 / 30.0)


def _judge_kinematically(
    context: RunContext, physics: PendingPhysics | None
) -> tuple[Verification, Timeline]:
    """The kinematic judge's verdict and timeline; each step it reads goes to ``physics``."""
    clock = time.perf_counter()
    viewing, trajectory = context.viewing, context.run.trajectory
    wait = wait_for_enter if viewing.step and not viewing.gui else None
    on_judged = None if physics is None else physics.judged
    looked_at = viewing.gui or viewing.meshcat
    with build_kitchen_for_task(context.task, gui=viewing.gui, kitchen_map=context.kitchen_map,
                                visuals=looked_at) as fresh:
        check_joint_count(context.run, fresh.robot.dof, context.trajectory_file)
        if viewing.meshcat and context.live is None:
            context.live = start_live_viewer(fresh)
        initial = fresh.scene.save_state()
        verification = verify_trajectory(fresh, context.task, trajectory, on_step=wait, on_judged=on_judged)
        timeline = build_timeline(trajectory, verification.tracks)
        if viewing.gui:
            fresh.scene.restore_state(initial)
            _play_in_window(fresh, timeline, viewing.step)
    context.report.verification = verification.report_data()
    context.report.timing["verification_s"] = time.perf_counter() - clock
    return verification, timeline


def _judged_while_planning(
    context: RunContext, followed: FollowingJudge
) -> tuple[Verification, Timeline] | None:
    """The kinematic verdict of the judge that followed the run, if it followed exactly the steps
    written (None: the file is to be judged now)."""
    clock = time.perf_counter()
    judged = followed.verdict(context.run.trajectory)
    if judged is None:
        return None
    verification = judged.verification
    context.report.verification = verification.report_data()
    context.report.timing["verification_s"] = time.perf_counter() - clock
    context.report.timing["verification_run_s"] = judged.seconds
    return verification, build_timeline(context.run.trajectory, verification.tracks)


def _physics_after_following(
    context: RunContext, followed: FollowingJudge, verification: Verification
) -> PhysicsOutcome | None:
    """Physics' outcome on the file the following judge read: its own if physics followed too,
    else executed now from the judge's reading (None with physics off)."""
    if followed.physics_job is not None:
        return _judge_physically(context, followed.physics)
    physics = _start_physics(context)
    if physics is None:
        return None
    for step, judged in judged_pairs(context.run.trajectory, verification):
        physics.judged(step, judged)
    return _judge_physically(context, physics.result)


def _spliced(run: SavedRun, after: int, rest: KitchenTrajectory) -> SavedRun:
    """``run`` with its steps after the first ``after`` replaced by ``rest``."""
    return replace(run, trajectory=KitchenTrajectory(run.trajectory.steps[:after] + rest.steps))


def _physics_job(task: Task, kitchen_map: KitchenMap, viewing: ViewingOptions,
                 replan: Replanner | None) -> PhysicsJob | None:
    """What physics executes, None with physics off."""
    return PhysicsJob(task, kitchen_map, replan, record=viewing.video) if viewing.physics else None


def following_judge(
    task: Task, kitchen_map: KitchenMap, viewing: ViewingOptions, replan: Replanner | None
) -> FollowingJudge | None:
    """The judges following a planning run's steps as it accepts them (`execute.following_judge`),
    unless the run is looked at while it is judged (a window, Meshcat, Enter per step) or the
    platform does not fork. Physics follows too unless the run renders its GIF: then physics
    (recording for replay.html) and the GIF share the second core once the plan is refined, and
    physics beside the planner would slow the planner more than it gains."""
    if viewing.gui or viewing.meshcat or viewing.step or not FollowingJudge.available():
        return None
    physics = None if viewing.video else _physics_job(task, kitchen_map, viewing, replan)
    return FollowingJudge(task, kitchen_map, physics)


def _start_physics(context: RunContext) -> PendingPhysics | None:
    """Execution under physics started beside the kinematic judge (None with physics off)."""
    replan = context.replan if len(context.replans) < MAX_REPLANS else None
    job = _physics_job(context.task, context.kitchen_map, context.viewing, replan)
    return None if job is None else PendingPhysics(job)


def _judge_physically(context: RunContext, result: Callable[[], PhysicsOutcome]) -> PhysicsOutcome:
    """Physics' verdict on the file (waiting for ``result()``); in a planning run, a re-plan where
    the scene drifted is written into the file, saying so (the caller judges it again)."""
    clock = time.perf_counter()
    outcome = result()
    report, execution = context.report, outcome.execution
    report.timing["physics_s"] = report_seconds(report, "physics_s") + time.perf_counter() - clock
    report.timing["physics_run_s"] = report_seconds(report, "physics_run_s") + outcome.seconds
    if not execution.verified and execution.replan is None:
        report.fail("physics", "; ".join(execution.problems[:3]) or "the goal does not hold under physics")
    if execution.replan is not None:
        context.replans.append(execution.replan.data())
        if execution.replan.trajectory is None:
            report.fail("physics", f"{execution.replan.reason}; no re-plan from the simulated scene")
        else:
            context.run = _spliced(context.run, execution.replan.after, execution.replan.trajectory)
            write_trajectory(context.trajectory_file, context.run)
            report.plan = context.run.trajectory.plan
            say(f"physics: {execution.replan.reason}; re-planned the rest and wrote it into "
                f"{context.trajectory_file.name}: judging the file again")
    execution.replans = list(context.replans)
    report.physics = execution.report_data()
    return outcome


def _start_pictures(context: RunContext) -> PendingPictures:
    """Starts drawing replay.gif (without it, joints.png) on the second core: the child gets ready
    while the judge reads the plan and draws once it is handed the judge's timeline."""
    run = context.run
    velocities = run.mode == "optimizes"
    title = f"{run.problem.name}, {run.mode}, seed {run.seed}: joint angles" + (
        " and velocities" if velocities else "")
    video = context.viewing.video
    job = PictureJob(context.task, context.kitchen_map, None, context.out_dir, title, velocities,
                     gif=video, joints=not video)
    return PendingPictures(job)


def judge_and_render(context: RunContext) -> int:
    """Judge ``context.run`` with both judges, plot and render it, write the report; the exit code.
    The verdicts of judges that followed the planning run (``context.followed``) are taken when
    they judged exactly the file; else physics executes each step on the second core as soon as
    the kinematic judge has read it (`background_physics`). The pictures of the judge's timeline
    are drawn beside what follows the judge, by a child that got ready meanwhile
    (`background_pictures`)."""
    pictures: PendingPictures | None = None
    physics: PendingPhysics | None = None
    followed, context.followed = context.followed, None
    try:
        while True:
            if pictures is not None:  # the file was re-planned: its pictures are drawn again
                pictures.cancel()
            pictures = _start_pictures(context)
            judged = None if followed is None else _judged_while_planning(context, followed)
            if followed is not None and judged is not None:
                verification, timeline = judged
                pictures.draw(timeline)
                outcome = _physics_after_following(context, followed, verification)
            else:
                physics = _start_physics(context)
                verification, timeline = _judge_kinematically(context, physics)
                pictures.draw(timeline)
                outcome = None if physics is None else _judge_physically(context, physics.result)
                physics = None
            followed = None  # a re-planned file is judged once written
            replan = None if outcome is None else outcome.execution.replan
            if replan is None or replan.trajectory is None:
                break
        if not verification.verified:
            context.report.fail("verification", "; ".join(verification.problems[:3]) or "verification failed")
        _render(context, timeline, None if outcome is None else outcome.recorded, pictures)
    except BaseException:
        for pending in (pictures, physics, followed):
            if pending is not None:
                pending.cancel()
        raise
    return finish(context.report, context.out_dir, context.inputs, context.report_name)


def _write_html(context: RunContext, timeline: Timeline, rollout: RecordedRollout | None) -> None:
    from kitchen_tamp.execute.render.browser_replay import HTML_FILE, write_timeline_replay  # Drake

    clock = time.perf_counter()
    report, path = context.report, context.out_dir / HTML_FILE
    if rollout is not None and rollout.captured:  # the motion the simulator executed
        report.outputs["html"] = rollout.write(path, context.live).name
        report.outputs["html_shows"] = "physics"
    else:
        with build_kitchen_for_task(context.task, kitchen_map=context.kitchen_map) as kitchen:
            report.outputs["html"] = write_timeline_replay(kitchen, timeline, path, context.live).name
        report.outputs["html_shows"] = "kinematic replay"
    report.timing["html_s"] = time.perf_counter() - clock


def _render(
    context: RunContext, timeline: Timeline, rollout: RecordedRollout | None, pictures: PendingPictures
) -> None:
    clock = time.perf_counter()
    report = context.report
    report.outputs["joints_plot"] = None
    report.outputs["gif"] = report.outputs["html"] = None
    joints_s = 0.0
    if context.viewing.video:
        _write_html(context, timeline, rollout)
    if not pictures.job.joints:
        joints, joints_s = pictures.job.draw_joints(timeline)
        report.outputs["joints_plot"] = joints.name
    waited = time.perf_counter()
    drawn = pictures.result()
    report.timing["pictures_wait_s"] = time.perf_counter() - waited
    report.timing["joints_s"] = joints_s + drawn.joints_s
    if drawn.joints is not None:
        report.outputs["joints_plot"] = drawn.joints.name
    if context.viewing.video:
        report.timing["gif_s"] = drawn.gif_s
        report.outputs["gif"] = None if drawn.gif is None else drawn.gif.name
        say(f"rendered {drawn.frames} frames of the replay")
    report.timing["rendering_s"] = time.perf_counter() - clock


def finish(report: RunReport, out_dir: Path, inputs: RunInputs, report_name: str = REPORT_FILE) -> int:
    """Write the report and print the verdict line; the exit code."""
    if report.started is not None:
        report.timing["total_s"] = time.perf_counter() - report.started
        report.timing["other_s"] = report.unaccounted_seconds()
    path = report.write(out_dir / report_name)
    write_profile(out_dir)
    verification = report.verification or {}
    files = inputs.words()
    if report.solved:
        goals = ", ".join(verification.get("goal_atoms", {}))  # type: ignore[arg-type]
        clearance = verification.get("min_clearance_m")
        margin = f"min clearance {clearance * 1000:.1f} mm" if isinstance(clearance, float) else "no motion"
        say(f"SOLVED and verified: {len(report.plan or [])} actions, collision-free ({margin}), goal {goals} "
            f"true; {report.verdicts()}; {files}; report {path}")
        return int(ExitCode.SOLVED)
    failure = report.failure or {}
    say(f"NOT SOLVED ({failure.get('stage')}): {failure.get('reason')}; {report.verdicts()}; {files}; "
        f"report {path}")
    return int(ExitCode.NO_PLAN)

