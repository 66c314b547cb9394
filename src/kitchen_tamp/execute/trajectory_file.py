"""``trajectory.json``: a refined plan as data, enough to replay and verify it without planning.

Per action: its PDDL text and its segments, each with joint waypoints, gripper
widths, the box the hand carries, the drawer joint values when a drawer moves
with the hand, and the contacts intended along it. Floats are written with full
precision, so a replay sees exactly what was planned.
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
from kitchen_tamp.world import AllowedContact

TRAJECTORY_FORMAT = "kitchen_tamp.trajectory/1"
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


def _contact_data(contact: AllowedContact) -> dict[str, Any]:
    links = None if contact.robot_links is None else sorted(contact.robot_links)
    return {"body": contact.body, "link": contact.link, "robot_links": links}


def _segment_data(segment: Segment) -> dict[str, Any]:
    return {
        "name": segment.name,
        "configurations": segment.configurations.tolist(),
        "gripper_widths": segment.gripper_widths.tolist(),
        "attached_box": segment.attached_box,
        "openable": segment.openable,
        "drawer_values": None if segment.drawer_values is None else segment.drawer_values.tolist(),
        "allowed_contacts": [_contact_data(c) for c in segment.allowed_contacts],
    }


def trajectory_data(run: SavedRun) -> dict[str, Any]:
    """The JSON document of a saved run."""
    return {
        "format": TRAJECTORY_FORMAT,
        "problem": str(run.problem),
        "domain": str(run.domain),
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


def _contact(data: dict[str, Any]) -> AllowedContact:
    links = data.get("robot_links")
    return AllowedContact(
        str(data["body"]), data.get("link"), None if links is None else frozenset(str(n) for n in links)
    )


def _segment(data: dict[str, Any]) -> Segment:
    drawer = data.get("drawer_values")
    return Segment(
        name=str(data["name"]),
        configurations=np.asarray(data["configurations"], dtype=float),
        gripper_widths=np.asarray(data["gripper_widths"], dtype=float),
        attached_box=data.get("attached_box"),
        openable=data.get("openable"),
        drawer_values=None if drawer is None else np.asarray(drawer, dtype=float),
        allowed_contacts=tuple(_contact(c) for c in data.get("allowed_contacts", [])),
    )


def read_trajectory(path: Path) -> SavedRun:
    """Read a saved run; ``TrajectoryFileError`` names the file and what is wrong."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise TrajectoryFileError(f"{path}: no such file (is this a run directory?)") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise TrajectoryFileError(f"{path}: not a readable JSON file ({error})") from None
    if not isinstance(data, dict) or data.get("format") != TRAJECTORY_FORMAT:
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
        )
    except (KeyError, TypeError, ValueError) as error:
        raise TrajectoryFileError(f"{path}: malformed trajectory ({error})") from None
