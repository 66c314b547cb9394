"""trajectory.json round-trips exactly, records its input files' digests, and a malformed file
-- every kind of wrong value -- is refused with one line naming the file, step, segment,
waypoint and field, before anything is interpolated."""

from __future__ import annotations

import copy
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.execute import SavedRun, TrajectoryFileError, read_trajectory, write_trajectory
from kitchen_tamp.execute.trajectory_file import check_joint_count, trajectory_data
from kitchen_tamp.kitchen import Segment
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory


def _small_run() -> SavedRun:
    """Two steps of two segments each, 7 joints, continuous (no kitchen needed)."""
    q = np.linspace(0.0, 0.1, 7)
    steps = []
    for action in ("(open drawer)", "(pickUp spam countertop)"):
        move = Segment("move", np.stack([q, q + 0.1]), np.full(2, 0.08))
        close = Segment("close", np.stack([q + 0.1, q + 0.1, q + 0.1]), np.array([0.08, 0.06, 0.05]))
        steps.append(ActionTrajectory(action, (move, close)))
        q = q + 0.1
    trajectory = KitchenTrajectory(tuple(steps))
    return SavedRun(Path("/p/problem.pddl"), Path("/p/domain.pddl"), "rrt", 3, trajectory,
                    scene=Path("/p/scene.toml"), sha256={"problem": "ab" * 32})


def test_round_trip_is_exact(tmp_path: Path) -> None:
    run = _small_run()
    back = read_trajectory(write_trajectory(tmp_path / "trajectory.json", run))
    assert (back.problem, back.domain, back.mode, back.seed) == (run.problem, run.domain, "rrt", 3)
    assert back.trajectory.plan == run.trajectory.plan and back.scene == run.scene
    assert dict(back.sha256) == {"problem": "ab" * 32}
    for mine, theirs in zip(run.trajectory.steps, back.trajectory.steps, strict=True):
        for a, b in zip(mine.segments, theirs.segments, strict=True):
            assert a.name == b.name
            assert np.array_equal(a.configurations, b.configurations)
            assert np.array_equal(a.gripper_widths, b.gripper_widths)
    assert back.ignored_fields == ()
    data = trajectory_data(run)
    del data["scene"], data["sha256"]
    (tmp_path / "old.json").write_text(json.dumps(data))
    old = read_trajectory(tmp_path / "old.json")  # written before scenes and digests were recorded
    assert old.scene is None and dict(old.sha256) == {}


def _waypoint(data: dict[str, Any]) -> list[Any]:
    row: list[Any] = data["steps"][1]["segments"][0]["configurations"][1]
    return row


def _set(value: object) -> Callable[[dict[str, Any]], None]:
    def change(data: dict[str, Any]) -> None:
        _waypoint(data)[3] = value
    return change


def _drop_joint(data: dict[str, Any]) -> None:
    _waypoint(data).pop()


def _null_action(data: dict[str, Any]) -> None:
    data["steps"][1]["action"] = None


def _widths_as_text(data: dict[str, Any]) -> None:
    data["steps"][0]["segments"][1]["gripper_widths"] = "0.08"


def _one_width_too_few(data: dict[str, Any]) -> None:
    data["steps"][0]["segments"][1]["gripper_widths"].pop()


def _no_configurations(data: dict[str, Any]) -> None:
    del data["steps"][0]["segments"][1]["configurations"]


def _seed_as_text(data: dict[str, Any]) -> None:
    data["seed"] = "3"


def _steps_as_object(data: dict[str, Any]) -> None:
    data["steps"] = {"action": "(open drawer)"}


def _jump_between_segments(data: dict[str, Any]) -> None:
    data["steps"][1]["segments"][1]["configurations"][0][0] += 0.5


def _jump_between_steps(data: dict[str, Any]) -> None:
    for row in data["steps"][1]["segments"][0]["configurations"][:1]:
        row[2] -= 0.3


def _boolean_width(data: dict[str, Any]) -> None:
    data["steps"][0]["segments"][0]["gripper_widths"][0] = True


def _empty_segments(data: dict[str, Any]) -> None:
    data["steps"][0]["segments"] = []


WHERE = "step 2 (pickUp spam countertop), segment 1 (move), waypoint 1"
MALFORMED: dict[str, tuple[Callable[[dict[str, Any]], None], str]] = {
    "NaN": (_set(float("nan")), f"{WHERE}: configurations holds nan, not a finite number"),
    "infinity": (_set(float("inf")), f"{WHERE}: configurations holds inf, not a finite number"),
    "1e12": (_set(1e12), f"{WHERE}: configurations holds 1000000000000.0, not a finite number within"),
    "a string": (_set("0.3"), f'{WHERE}: configurations holds "0.3", not a number'),
    "null joint": (_set(None), f"{WHERE}: configurations holds null, not a number"),
    "6 joints": (_drop_joint, f"{WHERE}: configurations has 6 joint values, the file's first waypoint 7"),
    "action null": (_null_action, "step 2: 'action' must be a non-empty string, got null"),
    "widths a string": (_widths_as_text, "step 1 (open drawer), segment 2 (close): gripper_widths must be"),
    "one width too few": (_one_width_too_few, "segment 2 (close): 2 gripper widths for 3 waypoints"),
    "no configurations": (_no_configurations, "segment 2 (close): 'configurations' must be a list of"),
    "seed a string": (_seed_as_text, 'seed: must be a non-negative integer, got "3"'),
    "steps not a list": (_steps_as_object, "steps: must be a list of steps"),
    "boolean width": (_boolean_width, "segment 1 (move): gripper_widths holds true, not a number"),
    "no segments": (_empty_segments, "step 1: 'segments' must be a non-empty list"),
    "segments apart": (_jump_between_segments, "segment 'close': starts 0.5 rad from where 'move' ends"),
    "steps apart": (_jump_between_steps, "step 2 (pickUp spam countertop): starts 0.3 rad from where"),
}


@pytest.mark.parametrize("mistake", sorted(MALFORMED))
def test_a_malformed_value_is_one_line_naming_where_it_is(tmp_path: Path, mistake: str) -> None:
    change, message = MALFORMED[mistake]
    data = copy.deepcopy(trajectory_data(_small_run()))
    change(data)
    path = tmp_path / "trajectory.json"
    path.write_text(json.dumps(data))  # json writes NaN and Infinity, as Python reads them
    with pytest.raises(TrajectoryFileError) as error:
        read_trajectory(path)
    text = str(error.value)
    assert text.startswith(f"{path}: ") and message in text, text
    assert "\n" not in text


def test_a_waypoint_count_other_than_the_robots_is_refused(tmp_path: Path) -> None:
    path = write_trajectory(tmp_path / "trajectory.json", _small_run())
    with pytest.raises(TrajectoryFileError, match="has 7 joint values, the robot has 6 joints"):
        check_joint_count(read_trajectory(path), 6, path)
    check_joint_count(read_trajectory(path), 7, path)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (None, "no such file"),
        ("{not json", "not a readable JSON"),
        ('{"format": "x"}', "not a kitchen_tamp"),
        ("[" * 100000, "not a readable JSON"),
        ('{"format": "kitchen_tamp.trajectory/2", "steps": [{}]}', "step 1: 'action' must be"),
    ],
)
def test_bad_files_are_refused_with_their_name(tmp_path: Path, content: str | None, message: str) -> None:
    path = tmp_path / "trajectory.json"
    if content is not None:
        path.write_text(content)
    with pytest.raises(TrajectoryFileError, match=message) as error:
        read_trajectory(path)
    assert str(path) in str(error.value)
