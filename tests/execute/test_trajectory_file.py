"""trajectory.json round-trips exactly, and bad files are refused with their name."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.execute import SavedRun, TrajectoryFileError, read_trajectory, write_trajectory
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory


def test_round_trip_is_exact(tmp_path: Path, refined: KitchenTrajectory) -> None:
    run = SavedRun(Path("/p/problem.pddl"), Path("/p/domain.pddl"), "rrt", 3, refined)
    back = read_trajectory(write_trajectory(tmp_path / "trajectory.json", run))
    assert (back.problem, back.domain, back.mode, back.seed) == (run.problem, run.domain, "rrt", 3)
    assert back.trajectory.plan == refined.plan
    for mine, theirs in zip(refined.steps, back.trajectory.steps, strict=True):
        for a, b in zip(mine.segments, theirs.segments, strict=True):
            assert a.name == b.name
            assert np.array_equal(a.configurations, b.configurations)
            assert np.array_equal(a.gripper_widths, b.gripper_widths)
    assert back.ignored_fields == ()
    assert back.scene is None  # a file that records no scene (written before scenes were recorded)
    with_scene = SavedRun(run.problem, run.domain, "rrt", 3, refined, scene=Path("/p/scene.toml"))
    assert read_trajectory(write_trajectory(tmp_path / "t2.json", with_scene)).scene == Path("/p/scene.toml")


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (None, "no such file"),
        ("{not json", "not a readable JSON"),
        ('{"format": "x"}', "not a kitchen_tamp"),
        ('{"format": "kitchen_tamp.trajectory/2", "steps": [{}]}', "malformed"),
    ],
)
def test_bad_files_are_refused_with_their_name(tmp_path: Path, content: str | None, message: str) -> None:
    path = tmp_path / "trajectory.json"
    if content is not None:
        path.write_text(content)
    with pytest.raises(TrajectoryFileError, match=message) as error:
        read_trajectory(path)
    assert str(path) in str(error.value)
