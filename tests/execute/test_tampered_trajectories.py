"""``final_project.py replay`` against a sceptic: doctored copies of a good run's
trajectory.json are each refused by the kinematic judge, with the step, the segment and the
cause named; the untouched copy is accepted. The first format's declarations (carried box,
drawer values, allowed contacts) excuse nothing. Malformed files exit 2 with one line.
(Physics' own refusals are in ``test_physics_execution.py``; swapped problem and scene
files in ``test_final_project.py``.)"""

from __future__ import annotations

import copy
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.cli.final_project import main
from kitchen_tamp.execute import TRAJECTORY_FILE
from kitchen_tamp.execute.trajectory_file import trajectory_data
from kitchen_tamp.kitchen import KitchenScene, build_kitchen_for_task
from kitchen_tamp.kitchen.action_replay import pull_direction
from kitchen_tamp.world import straight_line
from tests.conftest import KitchenRuns, PlannedRun

pytestmark = pytest.mark.slow  # each test replays a whole kitchen plan

EVERY_BODY = [{"body": name, "link": None, "robot_links": None} for name in ("kitchen", "spam", "sugar")]
"""The first format's contact declaration that excused anything."""

Data = dict[str, Any]


def _first_format(data: Data) -> Data:
    """The run in the first format, with its declarations: no box carried, no drawer moved."""
    old = copy.deepcopy(data)
    old["format"] = "kitchen_tamp.trajectory/1"
    for step in old["steps"]:
        for segment in step["segments"]:
            segment.update(attached_box=None, openable=None, drawer_values=None, allowed_contacts=[])
    return old


def _segment(data: Data, step: int, name: str) -> Data:
    return next(s for s in data["steps"][step]["segments"] if s["name"] == name)


def _replay(tmp_path: Path, data: Data, physics: bool = False) -> tuple[int, list[str]]:
    """Exit code of ``final_project.py replay`` (the kinematic judge only, unless ``physics``) on
    a run directory holding ``data``, and the problems its report lists."""
    run_dir = tmp_path / "run"
    run_dir.mkdir(parents=True)
    (run_dir / TRAJECTORY_FILE).write_text(json.dumps(data))
    code = main(["replay", str(run_dir), "--no-video", *([] if physics else ["--no-physics"])])
    report = json.loads((run_dir / "replay_report.json").read_text())
    return code, list(report["verification"]["problems"])


@pytest.fixture(scope="module")
def good(kitchen_runs: KitchenRuns) -> PlannedRun:
    return kitchen_runs.refined()


@pytest.fixture(scope="module")
def good_run(good: PlannedRun) -> Data:
    """The refined plan as trajectory.json data (current format), as a run writes it."""
    return trajectory_data(good.saved())


# -- the first format's declarations excuse nothing ----------------------------------------------
def _detour_into_the_cabinet(kitchen: KitchenScene, data: Data) -> None:
    """The first move goes through a pose with the hand 10 cm behind the drawer's handle,
    inside the cabinet, declaring every body an allowed contact."""
    grasp = np.array(_segment(data, 0, "approach")["configurations"][-1])
    world_from_tool = kitchen.robot.forward_kinematics(grasp)
    inside = world_from_tool.translated(0.10 * world_from_tool.rotation[:, 2])
    detour = kitchen.ik.solve(inside, np.random.default_rng(0), seeds=[grasp])
    assert detour is not None
    assert np.linalg.norm(kitchen.robot.forward_kinematics(detour).translation - inside.translation) < 0.01
    move = _segment(data, 0, "move")
    move["configurations"] = [move["configurations"][0], detour.tolist(), move["configurations"][-1]]
    move["gripper_widths"] = [move["gripper_widths"][0]] * 3
    move["allowed_contacts"] = EVERY_BODY


def _drawer_opens_with_the_hand_elsewhere(kitchen: KitchenScene, data: Data) -> None:
    """The fingers never close on the handle; the file says the drawer follows the pull."""
    open_width = _segment(data, 0, "approach")["gripper_widths"][0]
    for name in ("grip", "pull", "release"):
        segment = _segment(data, 0, name)
        segment["gripper_widths"] = [open_width] * len(segment["gripper_widths"])
        segment["allowed_contacts"] = EVERY_BODY
    pull = _segment(data, 0, "pull")
    pull["openable"] = "drawer"
    pull["drawer_values"] = np.linspace(0.0, 0.28, len(pull["configurations"])).tolist()


def _box_rides_with_a_distant_hand(kitchen: KitchenScene, data: Data) -> None:
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


def _grasp_of_the_wrong_box(kitchen: KitchenScene, data: Data) -> None:
    """The step says it picks the sugar from the stove; the hand grasps the spam."""
    data["steps"][1]["action"] = "(pickUp sugar stove)"
    _segment(data, 1, "lift")["attached_box"] = "sugar"
    for name in ("approach", "close"):
        _segment(data, 1, name)["allowed_contacts"] = EVERY_BODY


def _fingers_pressed_into_the_box(kitchen: KitchenScene, data: Data) -> None:
    """The fingers close 1 cm narrower than the spam is wide."""
    close, lift = _segment(data, 1, "close"), _segment(data, 1, "lift")
    squeezed = close["gripper_widths"][-1] - 0.01
    close["gripper_widths"][-1] = squeezed
    lift["gripper_widths"] = [squeezed] * len(lift["gripper_widths"])
    lift["attached_box"] = "spam"
    close["allowed_contacts"] = EVERY_BODY


# -- what the robot can do -------------------------------------------------------------------------
def _joint_past_its_safety_limit(kitchen: KitchenScene, data: Data) -> None:
    """A move through a waypoint with joint 4 at -0.03 rad: inside the URDF's <limit> (up to
    0), past its <safety_controller> (up to -0.0698)."""
    move = _segment(data, 0, "move")
    middle = list(move["configurations"][0])
    middle[3] = -0.03
    move["configurations"] = [move["configurations"][0], middle, move["configurations"][-1]]
    move["gripper_widths"] = [move["gripper_widths"][0]] * 3


def _fingers_wider_than_the_hand(kitchen: KitchenScene, data: Data) -> None:
    """The approach to the handle with the fingers 9 cm apart (the Panda opens 8 cm)."""
    approach = _segment(data, 0, "approach")
    approach["gripper_widths"] = [0.09] * len(approach["gripper_widths"])


def _negative_width(kitchen: KitchenScene, data: Data) -> None:
    """The fingers close to -1 mm around the spam."""
    _segment(data, 1, "close")["gripper_widths"][-1] = -0.001
    lift = _segment(data, 1, "lift")
    lift["gripper_widths"] = [-0.001] * len(lift["gripper_widths"])


# -- letting go ----------------------------------------------------------------------------------
def _slow_release_while_lifting(kitchen: KitchenScene, data: Data) -> None:
    """From half way up the lift, the fingers open by half a micrometre per waypoint (the judge
    used to skip changes of 1e-6 m or less)."""
    lift = _segment(data, 1, "lift")
    width, count = lift["gripper_widths"][0], len(lift["gripper_widths"])
    lift["gripper_widths"] = [width + 5e-7 * max(0, i - count // 2) for i in range(count)]


def _drop_and_grasp_again(kitchen: KitchenScene, data: Data) -> None:
    """Half way up the lift the fingers open fully, then close on the spam again."""
    lift = _segment(data, 1, "lift")
    widths = lift["gripper_widths"]
    middle = len(widths) // 2
    lift["gripper_widths"] = [*widths[:middle], 0.08, *widths[middle + 1 :]]


def _placed_from_above(kitchen: KitchenScene, data: Data) -> None:
    """The last place lets go of the sugar where its descent starts, 10 cm or more above the
    countertop (the last step: nothing after it need be continuous)."""
    descend, release, retreat = (_segment(data, 4, n) for n in ("descend", "release", "retreat"))
    high = descend["configurations"][0]
    for segment in (descend, release, retreat):
        segment["configurations"] = [high] * len(segment["configurations"])


# -- the drawer ------------------------------------------------------------------------------------
def _pull_segment(kitchen: KitchenScene, data: Data, displacement: np.ndarray) -> None:
    """The pull goes on by ``displacement`` (world, m) from where it ends, and comes back."""
    pull = _segment(data, 0, "pull")
    last = np.array(pull["configurations"][-1])
    world_from_tool = kitchen.robot.forward_kinematics(last)
    out = kitchen.ik.follow(last, straight_line(world_from_tool, displacement, 0.005), max_joint_step=0.2)
    assert out is not None
    extra = [q.tolist() for q in out[1:]] + [q.tolist() for q in out[-2::-1]]
    pull["configurations"] += extra
    pull["gripper_widths"] += [pull["gripper_widths"][-1]] * len(extra)


def _pulled_past_the_stop(kitchen: KitchenScene, data: Data) -> None:
    """Fully open, the hand holding the handle pulls 5 cm further (the drawer used to stop
    and the hand move on)."""
    _pull_segment(kitchen, data, 0.05 * pull_direction(kitchen, "drawer"))


def _hand_slides_off_the_slide(kitchen: KitchenScene, data: Data) -> None:
    """Holding the handle, the hand moves 1 cm across the drawer's slide and back."""
    axis = pull_direction(kitchen, "drawer")
    across = np.cross(axis, [0.0, 0.0, 1.0])
    _pull_segment(kitchen, data, 0.01 * across / np.linalg.norm(across))


Tamper = Callable[[KitchenScene, Data], None]
DOCTORED: dict[str, tuple[Tamper, str, bool]] = {
    # name: (doctoring, the start of the problem the judge names, whether in the first format)
    "detour": (_detour_into_the_cabinet, "step 1 (open drawer) move: collision", True),
    "drawer": (_drawer_opens_with_the_hand_elsewhere, "step 1 (open drawer) retreat (its last segment): the "
               "scene shows", True),
    "distant": (_box_rides_with_a_distant_hand, "step 2 (pickUp spam countertop) close: the fingers closed "
                "without holding spam", True),
    "wrong box": (_grasp_of_the_wrong_box, "step 2 (pickUp sugar stove) close: the fingers closed without "
                  "holding sugar", True),
    "pressed": (_fingers_pressed_into_the_box, "step 2 (pickUp spam countertop) close: collision", True),
    "safety limit": (_joint_past_its_safety_limit, "step 1 (open drawer) move: waypoint 1: panda_joint4 at "
                     "-0.0300 rad is past its upper limit -0.0698 rad (the stricter of", False),
    "too wide": (_fingers_wider_than_the_hand, "step 1 (open drawer) approach: waypoint 0: gripper width "
                 "0.0900 m is outside the hand's range [0, 0.080] m", False),
    "negative width": (_negative_width, "step 2 (pickUp spam countertop) close: waypoint 1: gripper width "
                       "-0.0010 m is outside the hand's range", False),
    "slow release": (_slow_release_while_lifting, "step 2 (pickUp spam countertop) lift: spam stands on "
                     "nothing after waypoint 5: it would fall", False),
    "drop and grasp": (_drop_and_grasp_again, "step 2 (pickUp spam countertop) lift: spam stands on nothing "
                       "after waypoint", False),
    "placed from above": (_placed_from_above, "step 5 (placeOn sugar countertop) release: sugar stands on "
                          "nothing after waypoint 0", False),
    "past the stop": (_pulled_past_the_stop, "step 1 (open drawer) pull: after waypoint", False),
    "off the slide": (_hand_slides_off_the_slide, "step 1 (open drawer) pull: after waypoint", False),
}
CAUSES = {"past the stop": "cm past its stop", "off the slide": "mm across the drawer's slide"}


@pytest.mark.parametrize("name", list(DOCTORED))
def test_replay_refuses_a_doctored_copy_naming_step_segment_and_cause(
    tmp_path: Path, good: PlannedRun, good_run: Data, name: str
) -> None:
    tamper, named, first_format = DOCTORED[name]
    data = _first_format(good_run) if first_format else copy.deepcopy(good_run)
    with build_kitchen_for_task(good.task) as kitchen:
        tamper(kitchen, data)
    code, problems = _replay(tmp_path, data)
    assert code == 1
    first = next((p for p in problems if p.startswith(named)), None)
    assert first is not None, problems
    assert CAUSES.get(name, "") in first, first
    if name == "detour":
        assert "kitchen/" in first and "mm deep" in first
    if name == "distant":
        assert any("(holding spam)" in p for p in problems if p.startswith("step 2")), problems
    if name == "pressed":
        assert "spam/panda/panda_leftfinger" in first and "mm deep" in first, first


def test_replay_accepts_the_untouched_copy(tmp_path: Path, good_run: Data) -> None:
    """As a run writes it, by both judges; the doctored copies above show the first format is
    read too."""
    code, problems = _replay(tmp_path, good_run, physics=True)
    assert code == 0 and problems == []


def _set_joint(value: object) -> Callable[[Data], None]:
    def change(data: Data) -> None:
        _segment(data, 1, "lift")["configurations"][2][3] = value

    return change


def _joints(count: int) -> Callable[[Data], None]:
    def change(data: Data) -> None:
        row = _segment(data, 1, "lift")["configurations"][2]
        del row[count:]

    return change


def _null_action(data: Data) -> None:
    data["steps"][2]["action"] = None


MALFORMED = {
    "NaN": (_set_joint(float("nan")), "configurations holds nan"),
    "infinity": (_set_joint(float("inf")), "configurations holds inf"),
    "1e12": (_set_joint(1e12), "configurations holds 1000000000000.0"),
    "6 joints": (_joints(6), "configurations has 6 joint values"),
    "action null": (_null_action, "step 3: 'action' must be a non-empty string, got null"),
}


@pytest.mark.parametrize("name", list(MALFORMED))
def test_a_malformed_file_exits_2_with_one_line(
    tmp_path: Path, good_run: Data, name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    change, detail = MALFORMED[name]
    data = copy.deepcopy(good_run)
    change(data)
    (tmp_path / TRAJECTORY_FILE).write_text(json.dumps(data))
    assert main(["replay", str(tmp_path), "--no-video"]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and detail in lines[0] and "Traceback" not in captured.err, captured.err
    if name != "action null":
        assert "step 2 (pickUp spam countertop), segment 4 (lift), waypoint 2: " in lines[0]
    assert not (tmp_path / "replay_report.json").exists()


def test_a_layout_that_overlaps_is_bad_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A tall box standing in a closed drawer goes through the counter: exit 2, both named."""
    problem = tmp_path / "overlap.pddl"
    problem.write_text(
        "(define (problem baguette-in-a-closed-drawer) (:domain kitchen)\n"
        "  (:objects stove countertop - surface drawer - openable baguette - box)\n"
        "  (:init (boxIn baguette drawer) (surfClear stove) (surfClear countertop) (armClear))\n"
        "  (:goal (and (boxOn baguette stove))))\n"
    )
    domain = Path(__file__).resolve().parents[2] / "pddl" / "domain.pddl"
    arguments = ["--problem", str(problem), "--domain", str(domain), "--no-video", "--out", str(tmp_path)]
    code = main(["rrt", *arguments])
    error = capsys.readouterr().err
    assert code == 2
    assert "overlapping bodies" in error and "baguette/baguette" in error and "kitchen/countertop" in error
    assert "Traceback" not in error
