"""Verification replays a trajectory in a fresh kitchen and catches what is wrong with it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from kitchen_tamp.execute import verify_trajectory
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import FREE_SPACE_SEGMENT, ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Task


def _verify(task: Task, trajectory: KitchenTrajectory) -> dict[str, object]:
    with build_kitchen_for_task(task) as kitchen:
        return verify_trajectory(kitchen, task, trajectory).report_data()


@pytest.mark.slow
def test_a_refined_plan_verifies(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    report = _verify(kitchen_task, refined)
    assert report["verified"] is True, report["problems"]
    assert report["collision_free"] is True
    assert report["goal_atoms"] == {"(boxIn spam drawer)": True, "(boxOn sugar countertop)": True}
    assert report["steps_as_planned"] == [True] * len(refined.steps)
    assert "(opened drawer)" in report["final_atoms"]  # type: ignore[operator]
    assert 0.0 <= float(report["min_clearance_m"]) < 0.5  # type: ignore[arg-type]
    assert int(report["configurations_checked"]) > 1000  # type: ignore[call-overload]


@pytest.mark.slow
def test_every_checked_state_is_close_to_the_next(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    from kitchen_tamp.kitchen.segment import LINEAR_STEP, interpolate_segment

    for step in refined.steps:
        for segment in step.segments:
            samples = interpolate_segment(segment, 0.005)
            assert np.allclose(samples.configurations[0], segment.configurations[0])
            assert np.allclose(samples.configurations[-1], segment.configurations[-1])
            assert np.all(np.linalg.norm(np.diff(samples.configurations, axis=0), axis=1) <= 0.005 + 1e-12)
            assert np.all(np.abs(np.diff(samples.gripper_widths)) <= LINEAR_STEP + 1e-12)


def _through(step: ActionTrajectory, detour: np.ndarray) -> ActionTrajectory:
    """The step with its free-space move sent through ``detour``."""
    move = step.segments[0]
    assert move.name == FREE_SPACE_SEGMENT
    qs = np.stack([move.configurations[0], detour, move.configurations[-1]])
    widths = np.full(3, move.gripper_widths[0])
    return ActionTrajectory(
        step.action, (dataclasses.replace(move, configurations=qs, gripper_widths=widths), *step.segments[1:])
    )


@pytest.mark.slow
def test_a_move_through_an_obstacle_is_caught_and_named(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        checker = kitchen.collision_checker()
        candidates = np.random.default_rng(0).uniform(checker.lower, checker.upper, size=(200, 7))
        colliding = candidates[~checker.is_valid(candidates)][0]
    steps = (_through(refined.steps[0], colliding), *refined.steps[1:])
    report = _verify(kitchen_task, KitchenTrajectory(steps))
    assert report["collision_free"] is False and report["verified"] is False
    assert float(report["min_clearance_m"]) < 0.0  # type: ignore[arg-type]
    assert any("step 1 (open drawer) move: collision" in p for p in report["problems"])  # type: ignore[attr-defined]


@pytest.mark.slow
def test_a_trajectory_that_stops_early_does_not_reach_the_goal(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    report = _verify(kitchen_task, KitchenTrajectory(refined.steps[:-1]))
    assert report["collision_free"] is True
    assert report["goal_atoms"] == {"(boxIn spam drawer)": True, "(boxOn sugar countertop)": False}
    assert report["verified"] is False


@pytest.mark.slow
def test_a_step_labelled_with_the_wrong_action_is_caught(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    first = refined.steps[1]
    relabelled = ActionTrajectory("(pickUp sugar stove)", first.segments)
    report = _verify(kitchen_task, KitchenTrajectory((refined.steps[0], relabelled, *refined.steps[2:])))
    assert report["verified"] is False
    assert report["steps_as_planned"][1] is False  # type: ignore[index]
