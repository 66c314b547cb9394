"""MotionBenchMaker's Panda problems: a scene and a request file (MoveIt YAML) to a planning problem.

MotionBenchMaker (Chamzas et al., RA-L 2022) publishes, per problem, a MoveIt planning scene
(``sceneNNNN.yaml``: ``world.collision_objects``, each an ``id``, ``primitives`` with ``type``
and ``dimensions``, ``primitive_poses`` with ``position`` and an ``orientation`` quaternion
x, y, z, w, and an optional object ``pose`` they are relative to; and an
``allowed_collision_matrix``) and a motion plan request (``requestNNNN.yaml``:
``start_state.joint_state`` names and positions, ``goal_constraints`` of joint constraints).
MoveIt's primitive dimensions: a box's full extents, a sphere's radius, a cylinder's height
then radius, along z. The files the benchmark reads ship in the ``vamp-planner`` source
distribution (``resources/panda/problems.tar.bz2``); this module reads their text.

The robot is MotionBenchMaker's Panda (``resources/panda/panda.urdf`` there, from
robowflex_resources): the same links, joint origins and collision meshes as the Panda of
``pybullet_data`` (byte for byte), standing at the world origin, with the fingers fixed 6.5 cm
out (our URDF's prismatic finger joints held there) and the joint ranges of its ``<limit>``
tags (wider than the datasheet's by 4 degrees; joint 4 reaches 0.0873 rad, not 0). Self pairs
are the ones its allowed-collision matrix does not allow.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import yaml

from kitchen_tamp.motion.geometry.primitive_scene import (
    ArmModel,
    ListedScene,
    PrimitiveObstacle,
    PrimitiveSceneError,
    arm_among_obstacles,
)

FloatArray = npt.NDArray[np.float64]

MBM_SCENARIOS = (
    "table_pick",
    "table_under_pick",
    "box",
    "bookshelf_small",
    "bookshelf_tall",
    "bookshelf_thin",
    "cage",
)
MBM_ARM_JOINTS = tuple(f"panda_joint{i}" for i in range(1, 8))
MBM_PANDA_LOWER = np.array([-2.9671, -1.8326, -2.9671, -3.1416, -2.9671, -0.0873, -2.9671])
"""The ``<limit>`` ranges of MotionBenchMaker's Panda URDF (what MoveIt and VAMP plan within)."""
MBM_PANDA_UPPER = np.array([2.9671, 1.8326, 2.9671, 0.0873, 2.9671, 3.8223, 2.9671])
MBM_FINGER_OPENING = 0.065
"""Each finger's offset (m) from the hand's centre in MotionBenchMaker's Panda (fixed joints there)."""
MBM_FINGER_JOINTS = ("panda_finger_joint1", "panda_finger_joint2")
MBM_GRIPPER_LINKS = frozenset({"panda_hand", "panda_leftfinger", "panda_rightfinger"})


class MbmFormatError(ValueError):
    """A scene or request file that is not a MotionBenchMaker problem; the message names the file
    and the key."""


@dataclass(frozen=True, eq=False)
class MbmProblem:
    """One problem: start (7,), goals (k, 7), the obstacles, and the robot link pairs checked."""

    scenario: str
    index: int
    start: FloatArray
    goals: FloatArray
    obstacles: tuple[PrimitiveObstacle, ...]
    self_pairs: tuple[tuple[str, str], ...]

    @property
    def name(self) -> str:
        return f"{self.scenario}-{self.index:04d}"


def _field(node: Any, key: str, where: str) -> Any:
    if not isinstance(node, dict) or key not in node:
        raise MbmFormatError(f"{where}: missing key {key!r}")
    return node[key]


def _numbers(node: Any, count: int, where: str) -> FloatArray:
    try:
        values = np.array(node, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise MbmFormatError(f"{where}: expected {count} numbers, got {node!r}") from None
    if values.shape != (count,) or not np.all(np.isfinite(values)):
        raise MbmFormatError(f"{where}: expected {count} finite numbers, got {node!r}")
    return values


def _pose(node: Any, where: str) -> FloatArray:
    """A MoveIt pose (position, orientation quaternion x, y, z, w) as a 4x4 matrix."""
    x, y, z, w = _numbers(_field(node, "orientation", where), 4, f"{where}.orientation")
    norm = float(np.sqrt(x * x + y * y + z * z + w * w))
    if norm < 1e-9:
        raise MbmFormatError(f"{where}.orientation: a zero quaternion")
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    pose = np.eye(4)
    pose[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    pose[:3, 3] = _numbers(_field(node, "position", where), 3, f"{where}.position")
    return pose


def _primitive(kind: Any, dimensions: Any, name: str, pose: FloatArray, where: str) -> PrimitiveObstacle:
    """MoveIt's dimensions as ours: a cylinder's (height, radius) becomes (radius, length)."""
    counts = {"box": 3, "sphere": 1, "cylinder": 2}
    if kind not in counts:
        raise MbmFormatError(f"{where}.type: unknown primitive {kind!r} (box, sphere or cylinder)")
    size = _numbers(dimensions, counts[kind], f"{where}.dimensions")
    if kind == "cylinder":
        size = size[::-1].copy()
    try:
        return PrimitiveObstacle(name, str(kind), size, pose)
    except PrimitiveSceneError as error:
        raise MbmFormatError(f"{where}: {error}") from None


def read_obstacles(scene: Any, where: str) -> tuple[PrimitiveObstacle, ...]:
    """Every primitive of every collision object of a parsed scene file."""
    objects = _field(_field(scene, "world", where), "collision_objects", f"{where}: world")
    obstacles = []
    for i, item in enumerate(objects or []):
        at = f"{where}: world.collision_objects[{i}]"
        name = str(_field(item, "id", at))
        base = _pose(item["pose"], f"{at}.pose") if isinstance(item, dict) and "pose" in item else np.eye(4)
        primitives, poses = _field(item, "primitives", at), _field(item, "primitive_poses", at)
        if not isinstance(primitives, list) or not isinstance(poses, list) or len(primitives) != len(poses):
            raise MbmFormatError(f"{at}: primitives and primitive_poses must be lists of one length")
        for k, (primitive, pose) in enumerate(zip(primitives, poses, strict=True)):
            kind = _field(primitive, "type", f"{at}.primitives[{k}]")
            dimensions = _field(primitive, "dimensions", f"{at}.primitives[{k}]")
            placed = base @ _pose(pose, f"{at}.primitive_poses[{k}]")
            label = name if len(primitives) == 1 else f"{name}_{k}"
            obstacles.append(_primitive(kind, dimensions, label, placed, f"{at}.primitives[{k}]"))
    return tuple(obstacles)


def read_checked_self_pairs(scene: Any, where: str) -> tuple[tuple[str, str], ...]:
    """The link pairs the scene's allowed-collision matrix does not allow (so they are checked)."""
    matrix = _field(scene, "allowed_collision_matrix", where)
    names = _field(matrix, "entry_names", f"{where}: allowed_collision_matrix")
    rows = _field(matrix, "entry_values", f"{where}: allowed_collision_matrix")
    if not isinstance(names, list) or not isinstance(rows, list) or len(rows) != len(names):
        raise MbmFormatError(f"{where}: allowed_collision_matrix: one row of entry_values per entry name")
    pairs = []
    for i, row in enumerate(rows):
        if not isinstance(row, list) or len(row) != len(names) or not all(isinstance(v, bool) for v in row):
            raise MbmFormatError(
                f"{where}: allowed_collision_matrix.entry_values[{i}]: {len(names)} booleans"
            )
        pairs += [(str(names[i]), str(names[j])) for j in range(i + 1, len(names)) if not row[j]]
    return tuple(pairs)


def _joint_values(names: Any, values: Any, wanted: Sequence[str], where: str) -> FloatArray:
    if not isinstance(names, list) or not isinstance(values, list) or len(names) != len(values):
        raise MbmFormatError(f"{where}: name and position must be lists of one length")
    missing = [n for n in wanted if n not in names]
    if missing:
        raise MbmFormatError(f"{where}: no position for {', '.join(missing)}")
    return _numbers([values[names.index(n)] for n in wanted], len(wanted), where)


def read_request(request: Any, where: str) -> tuple[FloatArray, FloatArray]:
    """(start (7,), goals (k, 7)) of a parsed request file: one goal per goal constraint set."""
    state = _field(_field(request, "start_state", where), "joint_state", f"{where}: start_state")
    at = f"{where}: start_state.joint_state"
    start = _joint_values(_field(state, "name", at), _field(state, "position", at), MBM_ARM_JOINTS, at)
    goals = []
    for i, constraint in enumerate(_field(request, "goal_constraints", where) or []):
        at = f"{where}: goal_constraints[{i}].joint_constraints"
        joints = _field(constraint, "joint_constraints", f"{where}: goal_constraints[{i}]")
        if not isinstance(joints, list):
            raise MbmFormatError(f"{at}: expected a list")
        names = [_field(j, "joint_name", at) for j in joints]
        goals.append(_joint_values(names, [_field(j, "position", at) for j in joints], MBM_ARM_JOINTS, at))
    if not goals:
        raise MbmFormatError(f"{where}: no goal_constraints")
    return start, np.array(goals)


def _parsed(text: str, where: str) -> Any:
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        line = f" line {mark.line + 1}" if mark is not None else ""
        raise MbmFormatError(f"{where}:{line} not YAML ({getattr(error, 'problem', error)})") from None


def read_mbm_problem(
    scenario: str, index: int, scene_text: str, request_text: str, where: Mapping[str, str] | None = None
) -> MbmProblem:
    """The problem of a scene file and a request file (their text); ``where`` names them in
    errors (keys ``scene`` and ``request``)."""
    names = dict(where or {})
    scene_where = names.get("scene", f"{scenario}/scene{index:04d}.yaml")
    request_where = names.get("request", f"{scenario}/request{index:04d}.yaml")
    scene = _parsed(scene_text, scene_where)
    start, goals = read_request(_parsed(request_text, request_where), request_where)
    return MbmProblem(
        scenario,
        index,
        start,
        goals,
        read_obstacles(scene, scene_where),
        read_checked_self_pairs(scene, scene_where),
    )


def mbm_panda(urdf_path: str | Path, self_pairs: Sequence[tuple[str, str]]) -> ArmModel:
    """MotionBenchMaker's Panda from the URDF at ``urdf_path`` (``pybullet_data``'s Panda: its
    links, joints and meshes are MotionBenchMaker's), fingers held open, MBM's joint ranges."""
    return ArmModel(
        urdf_path=str(urdf_path),
        arm_joints=MBM_ARM_JOINTS,
        lower=MBM_PANDA_LOWER,
        upper=MBM_PANDA_UPPER,
        held_joints=dict.fromkeys(MBM_FINGER_JOINTS, MBM_FINGER_OPENING),
        gripper_links=MBM_GRIPPER_LINKS,
        self_pairs=tuple(self_pairs),
        name="panda",
    )


def mbm_scene(problem: MbmProblem, panda_urdf: str | Path, directory: Path) -> ListedScene:
    """The problem's scene for the geometry models (its obstacles' URDF written to ``directory``)."""
    return arm_among_obstacles(mbm_panda(panda_urdf, problem.self_pairs), problem.obstacles, directory)
