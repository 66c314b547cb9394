"""Execution under physics: refined kitchen plans hold up in a simulated world with gravity and
friction grasps, a gripper opened in mid-air is caught naming the box, and the verdict is
deterministic."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.cli.final_project import main
from kitchen_tamp.execute import PhysicsExecution, SavedRun, execute_under_physics, write_trajectory
from kitchen_tamp.execute.physics.execution import FrameCallback
from kitchen_tamp.kitchen import KitchenScene, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Task, load_task
from kitchen_tamp.refinement import SamplingMotionBackend, refine_with_sesame
from kitchen_tamp.refinement.kitchen_sesame import sesame_replanner

pytestmark = pytest.mark.slow  # each test runs or replays a whole kitchen pipeline

REPO = Path(__file__).resolve().parents[2]


def _refine(problem: str, seed: int = 0) -> tuple[Task, KitchenTrajectory]:
    task = load_task(REPO / "pddl" / problem)
    with build_kitchen_for_task(task) as kitchen:
        refined = refine_with_sesame(kitchen, task, SamplingMotionBackend(), seed=seed).refined
    assert refined is not None
    return task, refined.trajectory


def test_the_kitchen_problem_holds_up_under_physics(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    result = execute_under_physics(kitchen_task, refined)
    assert result.verified, result.problems
    assert result.goal_reached and all(a.as_planned for a in result.actions)
    picks = [a for a in result.actions if a.action.startswith("(pickUp")]
    assert picks and all(a.held_box is not None for a in picks), "every pick ends with the box in the hand"
    for errors in result.final_box_errors.values():
        assert errors["position_error_m"] <= 0.02 and errors["tilt_deg"] <= 10.0
    data = result.report_data()
    assert data["verified"] is True and data["problems"] == []
    assert [a["action"] for a in data["actions"]] == refined.plan  # type: ignore[index]


@pytest.mark.parametrize("problem", ["problem_hard.pddl", "problem_baguette.pddl"])
def test_harder_problems_hold_up_under_physics(problem: str) -> None:
    task, trajectory = _refine(problem)
    result = execute_under_physics(task, trajectory)
    assert result.verified, result.problems


def _open_after_lift(trajectory: KitchenTrajectory, kitchen: KitchenScene) -> tuple[KitchenTrajectory, str]:
    """The trajectory with the gripper opened fully in the middle of the first pick's lift."""
    index = next(i for i, s in enumerate(trajectory.steps) if s.action.startswith("(pickUp"))
    step = trajectory.steps[index]
    box = step.action.strip("()").split()[1]
    lift = step.segments[-1]
    widths = lift.gripper_widths.copy()
    widths[len(widths) // 2 :] = kitchen.robot.max_gripper_width
    tampered = ActionTrajectory(step.action, (*step.segments[:-1], replace(lift, gripper_widths=widths)))
    steps = list(trajectory.steps)
    steps[index] = tampered
    return KitchenTrajectory(tuple(steps)), box


def test_a_gripper_opened_in_mid_air_fails_physics_naming_the_box(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        tampered, box = _open_after_lift(refined, kitchen)
    result = execute_under_physics(kitchen_task, tampered)
    assert not result.verified
    assert result.problems and any(box in problem for problem in result.problems), result.problems


def test_the_same_trajectory_gives_the_same_physics_verdict(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    first = execute_under_physics(kitchen_task, refined).report_data()
    second = execute_under_physics(kitchen_task, refined).report_data()
    assert first == second


def test_replay_exits_1_on_a_physics_failure_and_says_both_verdicts(
    kitchen_task: Task, refined: KitchenTrajectory, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        tampered, box = _open_after_lift(refined, kitchen)
    problem = REPO / "pddl" / "problem.pddl"
    saved = SavedRun(problem, problem.parent / "domain.pddl", "rrt", 0, tampered)
    write_trajectory(tmp_path / "trajectory.json", saved)
    assert main(["replay", str(tmp_path), "--no-video"]) == 1
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "physics: FAILED" in last and "kinematic judge:" in last and box in last
    kinematic_only = ["replay", str(tmp_path), "--no-video", "--no-physics", "--out", str(tmp_path / "k")]
    assert main(kinematic_only) in (0, 1)
    assert "physics: skipped" in capsys.readouterr().out


def test_on_frame_sees_the_simulated_clock(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    times: list[float] = []
    short = KitchenTrajectory(refined.steps[:1])
    execute_under_physics(kitchen_task, short, on_frame=lambda t, kitchen: times.append(t))
    assert len(times) > 10 and np.all(np.diff(times) > 0.0)


def _push_off_after(
    result: PhysicsExecution, kitchen_task: Task, action_prefix: str, box: str, push: float
) -> FrameCallback:
    """An ``on_frame`` that slides ``box`` by ``push`` metres towards the middle of the drawer
    while the scene settles after the first action starting with ``action_prefix``."""
    index = next(i for i, a in enumerate(result.actions) if a.action.startswith(action_prefix))
    when = result.actions[index].end_s - 0.09
    done: list[bool] = []

    def nudge(time_s: float, kitchen: KitchenScene) -> None:
        if done or time_s < when:
            return
        done.append(True)
        body = kitchen.box(box)
        pose = body.base_pose()
        toward = kitchen.openable_region("drawer").world_from_region.translation - pose.translation
        toward[2] = 0.0
        body.reset_base_pose(pose.translated(push * toward / np.linalg.norm(toward)))

    return nudge


def test_a_box_pushed_off_its_place_gets_the_rest_of_the_plan_refined_again(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    nominal = execute_under_physics(kitchen_task, refined)
    nudge = _push_off_after(nominal, kitchen_task, "(placeIn", "spam", 0.04)
    open_loop = execute_under_physics(kitchen_task, refined, on_frame=nudge)
    assert not open_loop.verified
    assert any("spam" in p and "planned pose" in p for p in open_loop.problems), open_loop.problems
    nudge = _push_off_after(nominal, kitchen_task, "(placeIn", "spam", 0.04)
    replan = sesame_replanner(SamplingMotionBackend(), seed=0)
    closed_loop = execute_under_physics(kitchen_task, refined, on_frame=nudge, replan=replan)
    assert len(closed_loop.replans) == 1 and "spam" in str(closed_loop.replans[0]["reason"])
    place = next(i for i, a in enumerate(refined.plan) if a.startswith("(placeIn"))
    assert closed_loop.replans[0]["plan"] == refined.plan[place + 1 :]
    assert closed_loop.verified, closed_loop.problems
