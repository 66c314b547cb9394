"""``trajectory.json``: a refined plan as data, enough to replay and verify it without planning.

Only what a planner decides: per action its PDDL text and its segments, each
with a name (a label for people), joint waypoints and gripper widths; and which
problem, domain and kitchen scene file the run planned in (paths, with the
SHA-256 of each: ``run_inputs``). What rides with the hand, where the drawer is
and which contacts are intended are not in the file: the judge derives them
(``kitchen_tamp.kitchen.replay_action``). Floats are written with full
precision, so a replay sees exactly what was planned.

Every value is checked before anything is interpolated: a wrong type, a missing
field, a number that is not finite or larger than ``LARGEST_VALUE``, waypoints
of different lengths, or a segment that does not start where the one before
ends is a ``TrajectoryFileError`` naming the step, segment, waypoint and field.

Files of the first format (``kitchen_tamp.trajectory/1``) are still read, but
the fields it also carried (``LEGACY_SEGMENT_FIELDS``: the carried box, the
drawer values, the allowed contacts) are ignored, never believed; the run
lists them in ``SavedRun.ignored_fields``.
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Final

import numpy as np

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.execute.run_inputs import INPUT_ROLES
from kitchen_tamp.kitchen import Segment
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory

TRAJECTORY_FORMAT = "kitchen_tamp.trajectory/2"
READABLE_FORMATS = ("kitchen_tamp.trajectory/1", TRAJECTORY_FORMAT)
"""Formats ``read_trajectory`` accepts; the first one's extra fields are ignored."""
LEGACY_SEGMENT_FIELDS = ("attached_box", "openable", "drawer_values", "allowed_contacts")
"""Segment fields of the first format that a judge must not take on trust, so never reads."""
TRAJECTORY_FILE = "trajectory.json"
LARGEST_VALUE: Final = 1000.0
"""No joint angle (rad) or gripper width (m) in a file is larger in magnitude: a larger one
is a malformed number, not a motion (the judge refuses values outside the robot's ranges)."""
CONTINUITY_TOLERANCE: Final = 1e-9
"""A segment starts where the one before it ends when no joint differs by more (rad)."""


class TrajectoryFileError(Exception):
    """A trajectory file that cannot be read (missing, not JSON, not our format, or a value of
    the wrong kind): one line naming the file and, where it lies, the step and the field."""


@dataclass(frozen=True, eq=False)
class SavedRun:
    """What a run saved for replay: where the problem came from, and the trajectory."""

    problem: Path
    domain: Path
    mode: str
    seed: int
    trajectory: KitchenTrajectory
    ignored_fields: tuple[str, ...] = ()
    """Fields the file carried that the judge derives instead (sorted; none in the current format)."""
    scene: Path | None = None
    """The kitchen scene file the run planned in (``None`` in files written before it was recorded)."""
    sha256: Mapping[str, str] = field(default_factory=dict)
    """Role (``problem``, ``domain``, ``scene``) -> SHA-256 of that file when the run planned."""

    def paths(self) -> dict[str, Path]:
        """Role -> recorded path of each input file."""
        paths = {"problem": self.problem, "domain": self.domain}
        return paths if self.scene is None else {**paths, "scene": self.scene}


def _segment_data(segment: Segment) -> dict[str, Any]:
    return {
        "name": segment.name,
        "configurations": segment.configurations.tolist(),
        "gripper_widths": segment.gripper_widths.tolist(),
    }


def trajectory_data(run: SavedRun) -> dict[str, Any]:
    """The JSON document of a saved run."""
    return {
        "format": TRAJECTORY_FORMAT,
        "problem": str(run.problem),
        "domain": str(run.domain),
        **({} if run.scene is None else {"scene": str(run.scene)}),
        **({"sha256": dict(run.sha256)} if run.sha256 else {}),
        "mode": run.mode,
        "seed": run.seed,
        "steps": [
            {"action": step.action, "segments": [_segment_data(s) for s in step.segments]}
            for step in run.trajectory.steps
        ],
    }


def write_trajectory(path: Path, run: SavedRun) -> Path:
    """Write ``run`` to ``path`` atomically."""
    return write_atomically(path, json.dumps(trajectory_data(run), indent=1) + "\n")


class _Reader:
    """Checks a parsed file value by value; every error names where in the file it is."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.joint_count: int | None = None

    def error(self, where: str, detail: str) -> TrajectoryFileError:
        return TrajectoryFileError(f"{self.path}: {where}: {detail}")

    def text(self, data: Mapping[str, Any], key: str, where: str) -> str:
        value = data.get(key)
        if not isinstance(value, str) or not value.strip():
            raise self.error(where, f"{key!r} must be a non-empty string, got {json.dumps(value)}")
        return value

    def mapping(self, value: object, where: str) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self.error(where, f"expected an object, got {json.dumps(value)[:60]}")
        return value

    def values(self, value: object, where: str, key: str) -> list[float]:
        """A list of finite numbers no larger than ``LARGEST_VALUE``."""
        if not isinstance(value, list):
            raise self.error(where, f"{key} must be a list of numbers, got {json.dumps(value)[:60]}")
        for number in value:
            if isinstance(number, bool) or not isinstance(number, int | float):
                raise self.error(where, f"{key} holds {json.dumps(number)[:60]}, not a number")
            if not math.isfinite(number) or abs(number) > LARGEST_VALUE:
                raise self.error(where, f"{key} holds {number!r}, not a finite number within "
                                 f"+-{LARGEST_VALUE:g}")
        return [float(v) for v in value]

    def segment(self, value: object, where: str) -> Segment:
        data = self.mapping(value, where)
        name = self.text(data, "name", where)
        where = f"{where} ({name})"
        waypoints = data.get("configurations")
        if not isinstance(waypoints, list) or len(waypoints) < 2:
            raise self.error(where, "'configurations' must be a list of at least two waypoints")
        rows = []
        for index, waypoint in enumerate(waypoints):
            row = self.values(waypoint, f"{where}, waypoint {index}", "configurations")
            if self.joint_count is None:
                self.joint_count = len(row)
            if len(row) != self.joint_count or not row:
                raise self.error(f"{where}, waypoint {index}", f"configurations has {len(row)} joint "
                                 f"values, the file's first waypoint {self.joint_count}")
            rows.append(row)
        widths = self.values(data.get("gripper_widths"), where, "gripper_widths")
        if len(widths) != len(rows):
            raise self.error(where, f"{len(widths)} gripper widths for {len(rows)} waypoints")
        return Segment(name, np.array(rows, dtype=float), np.array(widths, dtype=float))

    def step(self, value: object, index: int) -> ActionTrajectory:
        where = f"step {index + 1}"
        data = self.mapping(value, where)
        action = self.text(data, "action", where)
        segments = data.get("segments")
        if not isinstance(segments, list) or not segments:
            raise self.error(where, "'segments' must be a non-empty list")
        parsed = [self.segment(s, f"{where} {action}, segment {i + 1}") for i, s in enumerate(segments)]
        for before, after in itertools.pairwise(parsed):
            self.continues(before, after, f"{where} {action}, segment {after.name!r}")
        return ActionTrajectory(action, tuple(parsed))

    def continues(self, before: Segment, after: Segment, where: str) -> None:
        jump = float(np.max(np.abs(after.configurations[0] - before.configurations[-1])))
        if jump > CONTINUITY_TOLERANCE:
            raise self.error(where, f"starts {jump:.3g} rad from where {before.name!r} ends")

    def run(self, data: dict[str, Any]) -> SavedRun:
        steps_data = data.get("steps")
        if not isinstance(steps_data, list):
            raise self.error("steps", "must be a list of steps")
        steps = [self.step(s, i) for i, s in enumerate(steps_data)]
        for i, (before, after) in enumerate(itertools.pairwise(steps)):
            self.continues(before.segments[-1], after.segments[0], f"step {i + 2} {after.action}")
        seed = data.get("seed")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise self.error("seed", f"must be a non-negative integer, got {json.dumps(seed)}")
        digests = data.get("sha256", {})
        if not isinstance(digests, dict) or not all(
            role in INPUT_ROLES and isinstance(h, str) for role, h in digests.items()
        ):
            raise self.error("sha256", "must map problem, domain and scene to hex digests")
        keys = {key for s in steps_data for segment in s["segments"] for key in segment}
        ignored = keys & set(LEGACY_SEGMENT_FIELDS)
        scene = data.get("scene")
        return SavedRun(
            problem=Path(self.text(data, "problem", "problem")),
            domain=Path(self.text(data, "domain", "domain")),
            mode=self.text(data, "mode", "mode"),
            seed=seed,
            trajectory=KitchenTrajectory(tuple(steps)),
            ignored_fields=tuple(sorted(ignored)),
            scene=None if scene is None else Path(self.text(data, "scene", "scene")),
            sha256=dict(digests),
        )


def read_trajectory(path: Path) -> SavedRun:
    """Read and check a saved run; ``TrajectoryFileError`` names the file and what is wrong."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise TrajectoryFileError(f"{path}: no such file (is this a run directory?)") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, RecursionError) as error:
        raise TrajectoryFileError(f"{path}: not a readable JSON file ({error})") from None
    if not isinstance(data, dict) or data.get("format") not in READABLE_FORMATS:
        raise TrajectoryFileError(f"{path}: not a {TRAJECTORY_FORMAT} file")
    return _Reader(path).run(data)


def check_joint_count(run: SavedRun, joint_count: int, path: Path) -> None:
    """Raise ``TrajectoryFileError`` unless every waypoint has ``joint_count`` values (the
    robot's arm joints)."""
    for index, step in enumerate(run.trajectory.steps):
        segment = step.segments[0]
        if segment.configurations.shape[1] != joint_count:
            raise TrajectoryFileError(
                f"{path}: step {index + 1} {step.action}, segment 1 ({segment.name}), waypoint 0: "
                f"configurations has {segment.configurations.shape[1]} joint values, the robot has "
                f"{joint_count} joints"
            )
