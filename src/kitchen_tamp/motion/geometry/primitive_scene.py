"""A robot among primitive obstacles (boxes, spheres, cylinders) as a described scene.

Benchmarks and users whose worlds are lists of shapes (MotionBenchMaker's scenes, a table and
a few cans) reach the geometry models through the same `DescribedScene` the kitchen uses: the
obstacles are written out as one URDF (a root link and one link per obstacle, each on a fixed
joint at its pose), so Drake's model, the sphere model and PyBullet read them as they read any
body. ``ArmModel`` says which robot, where it stands, which joints plan and which pairs of its
links are checked against each other.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np
import numpy.typing as npt

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.motion.geometry.urdf import read_urdf

FloatArray = npt.NDArray[np.float64]

PRIMITIVE_KINDS = ("box", "sphere", "cylinder")
OBSTACLES_BODY = "obstacles"
"""The described body holding every obstacle."""
OBSTACLES_ROOT = "obstacles_root"
"""Its root link (no geometry), at the world origin."""


class PrimitiveSceneError(ValueError):
    """An obstacle or arm model that cannot be described; the message names it."""


@dataclass(frozen=True, eq=False)
class PrimitiveObstacle:
    """One shape at ``world_from_shape`` (4, 4). ``size``: a box's full extents (x, y, z), a
    sphere's (radius,), a cylinder's (radius, length) with its axis along the shape's z (URDF's
    convention, as `kitchen_tamp.motion.geometry.urdf.UrdfCollision`)."""

    name: str
    kind: str
    size: FloatArray
    world_from_shape: FloatArray

    def __post_init__(self) -> None:
        counts = {"box": 3, "sphere": 1, "cylinder": 2}
        if self.kind not in counts:
            raise PrimitiveSceneError(f"obstacle {self.name!r}: unknown kind {self.kind!r}")
        size = np.array(self.size, dtype=float).reshape(-1)
        if size.shape != (counts[self.kind],) or not np.all(np.isfinite(size)) or np.any(size <= 0.0):
            raise PrimitiveSceneError(
                f"obstacle {self.name!r}: a {self.kind} needs {counts[self.kind]} positive sizes, "
                f"got {size.tolist()}"
            )
        pose = np.array(self.world_from_shape, dtype=float)
        rotation = pose[:3, :3] if pose.shape == (4, 4) else np.zeros((3, 3))
        if not np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-6) or not np.all(np.isfinite(pose)):
            raise PrimitiveSceneError(f"obstacle {self.name!r}: the pose is not a rigid transform")
        object.__setattr__(self, "size", size)
        object.__setattr__(self, "world_from_shape", pose)


def rotation_rpy(rotation: FloatArray) -> tuple[float, float, float]:
    """URDF roll, pitch, yaw (fixed axes x, then y, then z) of a rotation matrix."""
    pitch = math.asin(max(-1.0, min(1.0, -float(rotation[2, 0]))))
    if abs(float(rotation[2, 0])) < 1.0 - 1e-12:
        roll = math.atan2(float(rotation[2, 1]), float(rotation[2, 2]))
        yaw = math.atan2(float(rotation[1, 0]), float(rotation[0, 0]))
    else:  # gimbal lock: only roll - yaw (or roll + yaw) is defined; yaw 0
        roll, yaw = math.atan2(-float(rotation[1, 2]), float(rotation[1, 1])), 0.0
    return roll, pitch, yaw


def _geometry_xml(obstacle: PrimitiveObstacle) -> str:
    size = [repr(float(v)) for v in obstacle.size]
    if obstacle.kind == "box":
        return f'<box size="{size[0]} {size[1]} {size[2]}"/>'
    if obstacle.kind == "sphere":
        return f'<sphere radius="{size[0]}"/>'
    return f'<cylinder radius="{size[0]}" length="{size[1]}"/>'


_INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
"""Every link's inertia (the obstacles never move; PyBullet warns about links without one)."""


def obstacles_urdf(obstacles: Sequence[PrimitiveObstacle]) -> str:
    """URDF text of the obstacles: link ``obstacles_root``, then link ``o<i>_<name>`` per obstacle
    (its collision shape at the link's origin) on a fixed joint at its pose."""
    parts = [
        f'<?xml version="1.0"?>\n<robot name="{OBSTACLES_BODY}">',
        f'  <link name="{OBSTACLES_ROOT}">{_INERTIAL}</link>',
    ]
    for link, obstacle in zip(obstacle_links(obstacles), obstacles, strict=True):
        x, y, z = (float(v) for v in obstacle.world_from_shape[:3, 3])
        roll, pitch, yaw = rotation_rpy(obstacle.world_from_shape[:3, :3])
        parts += [
            f'  <link name="{link}">{_INERTIAL}<collision><geometry>{_geometry_xml(obstacle)}</geometry>'
            "</collision></link>",
            f'  <joint name="{link}_joint" type="fixed"><parent link="{OBSTACLES_ROOT}"/>'
            f'<child link="{link}"/><origin xyz="{x!r} {y!r} {z!r}" rpy="{roll!r} {pitch!r} {yaw!r}"/>'
            "</joint>",
        ]
    return "\n".join([*parts, "</robot>", ""])


def obstacle_links(obstacles: Sequence[PrimitiveObstacle]) -> tuple[str, ...]:
    """The URDF link name of each obstacle: its index and its name's letters, digits and ``_``."""
    return tuple(
        f"o{i}_" + "".join(c if c.isalnum() or c == "_" else "_" for c in o.name)
        for i, o in enumerate(obstacles)
    )


@dataclass(frozen=True, eq=False)
class ArmModel:
    """A robot for a primitive scene: its URDF, base pose, planning joints with their limits,
    other joints held (a gripper's opening), gripper links, and the self pairs to check."""

    urdf_path: str
    arm_joints: tuple[str, ...]
    lower: FloatArray
    upper: FloatArray
    held_joints: Mapping[str, float]
    gripper_links: frozenset[str]
    self_pairs: tuple[tuple[str, str], ...]
    world_from_base: FloatArray = field(default_factory=lambda: np.eye(4))
    name: str = "robot"


@dataclass(frozen=True, eq=False)
class ListedBody:
    """A `DescribedBody` given by value."""

    name: str
    urdf_path: str
    base_link: str
    world_from_base: FloatArray
    joint_positions: Mapping[str, float]


@dataclass(frozen=True)
class ListedPair:
    """A `DescribedPair` given by value."""

    body_a: str
    link_a: str
    body_b: str
    link_b: str
    allowance: float = 0.0


@dataclass(frozen=True, eq=False)
class ListedScene:
    """A `DescribedScene` given by value (no attachments: nothing is carried)."""

    bodies: tuple[ListedBody, ...]
    robot: str
    arm_joints: tuple[str, ...]
    arm_lower: FloatArray
    arm_upper: FloatArray
    gripper_links: frozenset[str]
    checked_pairs: tuple[ListedPair, ...]
    attachments: tuple[()] = ()


def write_obstacles_urdf(obstacles: Sequence[PrimitiveObstacle], directory: Path) -> Path:
    """The obstacles' URDF in ``directory``, named by its content's digest (written once)."""
    text = obstacles_urdf(obstacles)
    path = directory / f"obstacles-{hashlib.sha256(text.encode()).hexdigest()[:20]}.urdf"
    if not path.is_file():
        write_atomically(path, text)
    return path


def arm_among_obstacles(
    arm: ArmModel, obstacles: Sequence[PrimitiveObstacle], directory: Path
) -> ListedScene:
    """The scene of ``arm`` among ``obstacles`` (their URDF written to ``directory``): every arm
    link with collision geometry checked against every obstacle, and ``arm.self_pairs``."""
    model = read_urdf(arm.urdf_path)
    shaped = sorted({shape.link for shape in model.collisions}, key=model.links.index)
    unknown = sorted({link for pair in arm.self_pairs for link in pair} - set(shaped))
    if unknown:
        raise PrimitiveSceneError(f"{arm.urdf_path}: self pairs name links without geometry: {unknown}")
    path = write_obstacles_urdf(obstacles, directory)
    pairs = [ListedPair(arm.name, a, arm.name, b) for a, b in arm.self_pairs]
    pairs += [
        ListedPair(arm.name, link, OBSTACLES_BODY, o) for link in shaped for o in obstacle_links(obstacles)
    ]
    held = {joint.name: 0.0 for joint in model.joints if joint.moves}
    held.update(arm.held_joints)
    bodies = (
        ListedBody(
            arm.name,
            arm.urdf_path,
            model.root,
            np.asarray(arm.world_from_base, dtype=float),
            MappingProxyType(held),
        ),
        ListedBody(OBSTACLES_BODY, str(path), OBSTACLES_ROOT, np.eye(4), MappingProxyType({})),
    )
    return ListedScene(
        bodies=bodies,
        robot=arm.name,
        arm_joints=arm.arm_joints,
        arm_lower=np.asarray(arm.lower, dtype=float),
        arm_upper=np.asarray(arm.upper, dtype=float),
        gripper_links=arm.gripper_links,
        checked_pairs=tuple(pairs),
    )
