"""``trajectory.json``: a refined plan as data, enough to replay and verify it without planning.

Only what a planner decides: per action its PDDL text and its segments, each
with a name (a label for people), joint waypoints and gripper widths; and which
problem, domain and kitchen scene file the run planned in (paths), so that
``replay`` judges it in the same kitchen. What rides
with the hand, where the drawer is and which contacts are intended are not in
the file: the judge derives them (``kitchen_tamp.kitchen.replay_action``).
Floats are written with full precision, so a replay sees exactly what was
planned.

Files of the first format (``kitchen_tamp.trajectory/1``) are still read, but
the fields it also carried (``LEGACY_SEGMENT_FIELDS``: the carried box, the
drawer values, the allowed contacts) are ignored, never believed; the run
lists them in ``SavedRun.ignored_fields``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.kitchen import Segment
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory

TRAJECTORY_FORMAT = "kitchen_tamp.trajectory/2"
READABLE_FORMATS = ("kitchen_tamp.trajectory/1", TRAJECTORY_FORMAT)
"""Formats ``read_trajectory`` accepts; the first one's extra fields are ignored."""
LEGACY_SEGMENT_FIELDS = ("attached_box", "openable", "drawer_values", "allowed_contacts")
"""Segment fields of the first format that a judge must not take on trust, so never reads."""
TRAJECTORY_FILE = "trajectory.json"


class TrajectoryFileError(Exception):
    """A trajectory file that cannot be read (missing, not JSON, or not our format)."""


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


def _segment(data: dict[str, Any]) -> Segment:
    return Segment(
        name=str(data["name"]),
        configurations=np.asarray(data["configurations"], dtype=float),
        gripper_widths=np.asarray(data["gripper_widths"], dtype=float),
    )


def read_trajectory(path: Path) -> SavedRun:
    """Read a saved run; ``TrajectoryFileError`` names the file and what is wrong."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise TrajectoryFileError(f"{path}: no such file (is this a run directory?)") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise TrajectoryFileError(f"{path}: not a readable JSON file ({error})") from None
    if not isinstance(data, dict) or data.get("format") not in READABLE_FORMATS:
        raise TrajectoryFileError(f"{path}: not a {TRAJECTORY_FORMAT} file")
    try:
        steps = tuple(
            ActionTrajectory(str(step["action"]), tuple(_segment(s) for s in step["segments"]))
            for step in data["steps"]
        )
        return SavedRun(
            problem=Path(data["problem"]),
            domain=Path(data["domain"]),
            mode=str(data["mode"]),
            seed=int(data["seed"]),
            trajectory=KitchenTrajectory(steps),
            ignored_fields=tuple(
                sorted(
                    {key for step in data["steps"] for s in step["segments"] for key in s}
                    & set(LEGACY_SEGMENT_FIELDS)
                )
            ),
            scene=Path(data["scene"]) if data.get("scene") is not None else None,
        )
    except (KeyError, TypeError, ValueError) as error:
        raise TrajectoryFileError(f"{path}: malformed trajectory ({error})") from None
