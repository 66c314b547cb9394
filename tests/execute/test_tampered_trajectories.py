"""``final_project.py replay`` believes nothing but configurations and gripper widths: tampered
copies of a good run's trajectory.json are refused, each with the step and segment named,
even when they carry the first format's declarations (carried box, drawer values, allowed
contacts) that used to excuse them; the untouched copy is accepted."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.cli.final_project import main
from kitchen_tamp.execute import TRAJECTORY_FILE, SavedRun
from kitchen_tamp.execute.trajectory_file import trajectory_data
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task
from tests.execute.conftest import PROBLEM

pytestmark = pytest.mark.slow  # each test runs or replays a whole kitchen pipeline

EVERY_BODY = [{"body": name, "link": None, "robot_links": None} for name in ("kitchen", "spam", "sugar")]
"""The first format's contact declaration that excused anything."""


def _first_format(data: dict[str, Any]) -> dict[str, Any]:
    """The run in the first format, with its declarations: no box carried, no drawer moved."""
    old = copy.deepcopy(data)
    old["format"] = "kitchen_tamp.trajectory/1"
    for step in old["steps"]:
        for segment in step["segments"]:
            segment.update(attached_box=None, openable=None, drawer_values=None, allowed_contacts=[])
    return old


def _segment(data: dict[str, Any], step: int, name: str) -> dict[str, Any]:
    return next(s for s in data["steps"][step]["segments"] if s["name"] == name)


def _replay(tmp_path: Path, data: dict[str, Any]) -> tuple[int, list[str]]:
    """Exit code of ``final_project.py replay`` on a run directory holding ``data``, and the
    problems its report lists."""
    run_dir = tmp_path / "run"
    run_dir.mkdir(parents=True)
    (run_dir / TRAJECTORY_FILE).write_text(json.dumps(data))
    code = main(["replay", str(run_dir), "--no-video"])
    report = json.loads((run_dir / "replay_report.json").read_text())
    return code, list(report["verification"]["problems"])


@pytest.fixture(scope="module")
def good_run(kitchen_task: Task, refined: KitchenTrajectory) -> dict[str, Any]:
    """The refined plan as trajectory.json data (current format)."""
    return trajectory_data(SavedRun(PROBLEM, PROBLEM.parent / "domain.pddl", "rrt", 0, refined))


def _detour_into_the_cabinet(task: Task, refined: KitchenTrajectory, data: dict[str, Any]) -> None:
    """The first move goes through a pose with the hand 10 cm behind the drawer's handle,
    inside the cabinet, declaring every body an allowed contact."""
    opening = refined.steps[0]
    grasp = next(s for s in opening.segments if s.name == "approach").configurations[-1]
    with build_kitchen_for_task(task) as kitchen:
        world_from_tool = kitchen.robot.forward_kinematics(grasp)
        inside = world_from_tool.translated(0.10 * world_from_tool.rotation[:, 2])
        detour = kitchen.ik.solve(inside, np.random.default_rng(0), seeds=[grasp])
        assert detour is not None
        reached = kitchen.robot.forward_kinematics(detour).translation
        assert np.linalg.norm(reached - inside.translation) < 0.01
    move = _segment(data, 0, "move")
    move["configurations"] = [move["configurations"][0], detour.tolist(), move["configurations"][-1]]
    move["gripper_widths"] = [move["gripper_widths"][0]] * 3
    move["allowed_contacts"] = EVERY_BODY


def _drawer_opens_with_the_hand_elsewhere(data: dict[str, Any]) -> None:
    """The fingers never close on the handle; the file says the drawer follows the pull."""
    open_width = _segment(data, 0, "approach")["gripper_widths"][0]
    for name in ("grip", "pull", "release"):
        segment = _segment(data, 0, name)
        segment["gripper_widths"] = [open_width] * len(segment["gripper_widths"])
        segment["allowed_contacts"] = EVERY_BODY
    pull = _segment(data, 0, "pull")
    pull["openable"] = "drawer"
    pull["drawer_values"] = np.linspace(0.0, 0.28, len(pull["configurations"])).tolist()


def _box_rides_with_a_distant_hand(data: dict[str, Any]) -> None:
    """The pick closes the fingers where the approach starts, 9 cm short of the spam, and the
    file says the spam rides with the hand."""
    approach, close, lift = (_segment(data, 1, n) for n in ("approach", "close", "lift"))
    back = approach["configurations"][0]
    approach["configurations"] = [back, back]
    approach["gripper_widths"] = approach["gripper_widths"][:2]
    close["configurations"] = [back, back]
    lift["configurations"] = [back, lift["configurations"][-1]]
    lift["gripper_widths"] = [lift["gripper_widths"][0]] * 2
    lift["attached_box"] = "spam"


def _grasp_of_the_wrong_box(data: dict[str, Any]) -> None:
    """The step says it picks the sugar from the stove; the hand grasps the spam."""
    data["steps"][1]["action"] = "(pickUp sugar stove)"
    _segment(data, 1, "lift")["attached_box"] = "sugar"
    for name in ("approach", "close"):
        _segment(data, 1, name)["allowed_contacts"] = EVERY_BODY


def _fingers_pressed_into_the_box(data: dict[str, Any]) -> None:
    """The fingers close 1 cm narrower than the spam is wide."""
    close, lift = _segment(data, 1, "close"), _segment(data, 1, "lift")
    squeezed = close["gripper_widths"][-1] - 0.01
    close["gripper_widths"][-1] = squeezed
    lift["gripper_widths"] = [squeezed] * len(lift["gripper_widths"])
    lift["attached_box"] = "spam"
    close["allowed_contacts"] = EVERY_BODY


@pytest.mark.parametrize(
    ("tamper", "named"),
    [
        ("detour", "step 1 (open drawer) move: collision"),
        ("drawer", "step 1 (open drawer) retreat (its last segment): the scene shows"),
        ("distant", "step 2 (pickUp spam countertop) close: the fingers closed without holding spam"),
        ("wrong box", "step 2 (pickUp sugar stove) close: the fingers closed without holding sugar"),
        ("pressed", "step 2 (pickUp spam countertop) close: collision"),
    ],
)
def test_replay_refuses_a_tampered_copy_naming_step_and_segment(
    tmp_path: Path,
    kitchen_task: Task,
    refined: KitchenTrajectory,
    good_run: dict[str, Any],
    tamper: str,
    named: str,
) -> None:
    data = _first_format(good_run)
    if tamper == "detour":
        _detour_into_the_cabinet(kitchen_task, refined, data)
    elif tamper == "drawer":
        _drawer_opens_with_the_hand_elsewhere(data)
    elif tamper == "distant":
        _box_rides_with_a_distant_hand(data)
    elif tamper == "wrong box":
        _grasp_of_the_wrong_box(data)
    else:
        _fingers_pressed_into_the_box(data)
    code, problems = _replay(tmp_path, data)
    assert code == 1
    assert any(p.startswith(named) for p in problems), problems
    if tamper == "detour":
        first = next(p for p in problems if p.startswith(named))
        assert "kitchen/" in first and "mm deep" in first
    if tamper == "distant":
        assert any("(holding spam)" in p for p in problems if p.startswith("step 2")), problems
    if tamper == "pressed":
        first = next(p for p in problems if p.startswith(named))
        assert "spam/panda/panda_leftfinger" in first and "mm deep" in first, first


def test_replay_accepts_the_untouched_copy(tmp_path: Path, good_run: dict[str, Any]) -> None:
    """As a run writes it; the tampered copies above show the first format is read too."""
    code, problems = _replay(tmp_path, good_run)
    assert code == 0 and problems == []


def test_a_layout_that_overlaps_is_bad_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A tall box standing in a closed drawer goes through the counter: exit 2, both named."""
    problem = tmp_path / "overlap.pddl"
    problem.write_text(
        "(define (problem baguette-in-a-closed-drawer) (:domain kitchen)\n"
        "  (:objects stove countertop - surface drawer - openable baguette - box)\n"
        "  (:init (boxIn baguette drawer) (surfClear stove) (surfClear countertop) (armClear))\n"
        "  (:goal (and (boxOn baguette stove))))\n"
    )
    domain = PROBLEM.parent / "domain.pddl"
    arguments = ["--problem", str(problem), "--domain", str(domain), "--no-video", "--out", str(tmp_path)]
    code = main(["rrt", *arguments])
    error = capsys.readouterr().err
    assert code == 2
    assert "overlapping bodies" in error and "baguette/baguette" in error and "kitchen/countertop" in error
    assert "Traceback" not in error
