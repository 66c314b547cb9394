"""Both judges following a planning run's steps as they are accepted: the verdicts of judging the
finished file, also when steps are taken back; a file that is not what was followed gets no verdict."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from kitchen_tamp.execute import Verification, execute_under_physics, judged_pairs
from kitchen_tamp.execute.following_judge import MAX_STARTS, FollowingJudge
from kitchen_tamp.execute.physics.background_physics import PhysicsJob
from kitchen_tamp.kitchen import default_kitchen_map
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Task

pytestmark = pytest.mark.slow  # each test judges a whole kitchen plan, physics included


def _judge(task: Task, physics: bool = True) -> FollowingJudge:
    job = PhysicsJob(task, default_kitchen_map(), replan=None, record=False) if physics else None
    return FollowingJudge(task, default_kitchen_map(), job)


def _nudged(step: ActionTrajectory) -> ActionTrajectory:
    """The same action with its last segment's last waypoint moved a hair (another sample)."""
    last = step.segments[-1]
    configurations = last.configurations.copy()
    configurations[-1, 0] += 1e-4
    moved = Segment(last.name, configurations, last.gripper_widths)
    return ActionTrajectory(step.action, (*step.segments[:-1], moved))


def test_following_gives_the_verdicts_of_judging_the_file(
    kitchen_task: Task, refined: KitchenTrajectory, verified: Verification
) -> None:
    judge = _judge(kitchen_task)
    for index, step in enumerate(refined.steps):
        judge.accepted(0, index, step)
    judged = judge.verdict(refined)
    assert judged is not None and judge.starts == 1
    assert judged.verification.report_data() == verified.report_data()
    physics = judge.physics().execution
    alone = execute_under_physics(kitchen_task, judged_pairs(refined, verified))
    assert physics.report_data() == alone.report_data()


def test_steps_taken_back_are_judged_again(
    kitchen_task: Task, refined: KitchenTrajectory, verified: Verification
) -> None:
    """A second plan's first steps, then a step taken back and sampled again: a new child judges
    the steps accepted since, and the verdict is the file's."""
    steps = refined.steps
    judge = _judge(kitchen_task, physics=False)
    judge.accepted(0, 0, steps[0])
    judge.accepted(1, 0, steps[0])  # another abstract plan
    judge.accepted(1, 1, _nudged(steps[1]))
    judge.accepted(1, 1, steps[1])  # step 2 taken back and sampled again
    for index in range(2, len(steps)):
        judge.accepted(1, index, steps[index])
    assert judge.starts == 3
    judged = judge.verdict(refined)
    assert judged is not None
    assert judged.verification.report_data() == verified.report_data()


def _copied(trajectory: KitchenTrajectory) -> KitchenTrajectory:
    """The same values in new arrays (as read back from the file)."""
    return KitchenTrajectory(tuple(
        ActionTrajectory(step.action, tuple(Segment(s.name, s.configurations.copy(), s.gripper_widths.copy())
                                            for s in step.segments))
        for step in trajectory.steps))


def test_the_file_must_hold_the_steps_followed_value_for_value(
    kitchen_task: Task, refined: KitchenTrajectory
) -> None:
    for written, judged in ((_copied(refined), True), (_nudged_last(refined), False)):
        judge = _judge(kitchen_task, physics=False)
        for index, step in enumerate(refined.steps):
            judge.accepted(0, index, step)
        assert (judge.verdict(written) is not None) == judged
        assert not judge.following


def _nudged_last(trajectory: KitchenTrajectory) -> KitchenTrajectory:
    return KitchenTrajectory((*trajectory.steps[:-1], _nudged(trajectory.steps[-1])))


def test_following_gives_up_after_too_many_starts(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    judge = _judge(kitchen_task, physics=False)
    for plan in range(MAX_STARTS + 1):
        judge.accepted(plan, 0, refined.steps[0])
    assert not judge.following
    for index in range(1, len(refined.steps)):
        judge.accepted(MAX_STARTS, index, refined.steps[index])
    assert judge.verdict(refined) is None


def _descendants(pid: int) -> set[int]:
    """The processes under ``pid`` (Linux's /proc)."""
    found, todo = set(), [pid]
    while todo:
        parent = todo.pop()
        for task in Path(f"/proc/{parent}/task").glob("*"):
            children = {int(child) for child in (task / "children").read_text().split()}
            found |= children
            todo.extend(children)
    return found


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="reads the process tree from Linux's /proc")
def test_a_stopped_child_takes_physics_child_with_it(kitchen_task: Task, refined: KitchenTrajectory) -> None:
    judge = _judge(kitchen_task)
    judge.accepted(0, 0, refined.steps[0])
    deadline = time.monotonic() + 30.0
    while len(first := _descendants(os.getpid())) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)  # the judge's child starts physics' own
    assert len(first) >= 2
    judge.accepted(1, 0, refined.steps[0])  # another plan: that child is stopped
    assert not any(Path(f"/proc/{pid}").exists() for pid in first)
    judge.cancel()
