"""A plain-data picture of a scene for other collision models (Drake), without PyBullet objects.

``describe_scene`` records, for every body, the URDF it was loaded from, where
its base is and where its movable joints are; which bodies ride on which links
and how; the robot's arm joints, limits and gripper links; and the link pairs a
collision check checks, each with the depth it may touch (the pair policy of
``checked_pairs``, decided there once for every collision model).
``describe_collision_checker`` does the same for the scene as a
``PyBulletCollisionChecker`` captured it. Poses are 4x4 homogeneous matrices
(``a_from_b`` maps b-coordinates to a), frames are URDF link frames.

Each body's URDF is the file the ``Scene`` loaded it from, unless the caller
names others (``urdf_paths``: body name -> path).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from kitchen_tamp.read_only_mappings import read_only
from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.collision.checked_pairs import CheckedLinkPair, CheckedPairs
from kitchen_tamp.world.collision.checker import AllowedContact, PyBulletCollisionChecker
from kitchen_tamp.world.errors import UnknownNameError
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray


def _frozen(array: FloatArray) -> FloatArray:
    copy = np.array(array, dtype=float)
    copy.flags.writeable = False
    return copy


@dataclass(frozen=True, eq=False)
class BodyDescription:
    """One loaded URDF: where its base link is and where its movable joints are."""

    name: str
    urdf_path: str
    base_link: str
    world_from_base: FloatArray
    """(4, 4): the base link's URDF frame in the world."""
    joint_positions: Mapping[str, float]
    """Every movable joint by name."""


@dataclass(frozen=True, eq=False)
class AttachmentDescription:
    """Body ``child``'s base link stays at ``parent_link_from_child`` (4, 4) in ``parent``'s link."""

    parent: str
    parent_link: str
    child: str
    parent_link_from_child: FloatArray


@dataclass(frozen=True, eq=False)
class SceneDescription:
    """Everything a collision model needs to rebuild a scene snapshot and check the arm in it.

    ``checked_pairs`` are exactly the pairs ``PyBulletCollisionChecker`` checks
    (see ``kitchen_tamp.world.collision.checked_pairs``), each with the penetration it may
    reach (an intended contact's bound; 0 for the rest).
    """

    bodies: tuple[BodyDescription, ...]
    attachments: tuple[AttachmentDescription, ...]
    robot: str
    arm_joints: tuple[str, ...]
    arm_lower: FloatArray
    arm_upper: FloatArray
    gripper_links: frozenset[str]
    checked_pairs: tuple[CheckedLinkPair, ...]

    def body(self, name: str) -> BodyDescription:
        """The body called ``name``."""
        for body in self.bodies:
            if body.name == name:
                return body
        raise UnknownNameError(f"the scene description has no body {name!r}")

    @property
    def arm_configuration(self) -> FloatArray:
        """The arm's joint positions in the snapshot."""
        joints = self.body(self.robot).joint_positions
        return np.array([joints[name] for name in self.arm_joints])

    @property
    def carried(self) -> tuple[str, ...]:
        """Names of the bodies attached to the robot."""
        return tuple(a.child for a in self.attachments if a.parent == self.robot)


def describe_scene(
    scene: Scene,
    robot: Robot,
    urdf_paths: Mapping[str, Path | str] | None = None,
    allowed: Iterable[AllowedContact] = (),
    attachments: Sequence[Attachment] | None = None,
) -> SceneDescription:
    """The scene as it is now (with ``attachments`` instead of the scene's, when given).

    Raises ``UnknownNameError`` when a body has no entry in ``urdf_paths``.
    """
    urdf_paths = scene.urdf_paths if urdf_paths is None else urdf_paths
    missing = sorted(b.name for b in scene.bodies if b.name not in urdf_paths)
    if missing:
        raise UnknownNameError(f"no URDF path given for bodies {', '.join(missing)}")
    bodies = []
    for body in scene.bodies:
        names = [j.name for j in body.joints if j.movable]
        values = body.joint_positions(names) if names else np.zeros(0)
        bodies.append(
            BodyDescription(
                name=body.name,
                urdf_path=str(Path(urdf_paths[body.name]).resolve()),
                base_link=body.base_link_name,
                world_from_base=_frozen(body.base_pose().matrix()),
                joint_positions=read_only(dict(zip(names, map(float, values), strict=True))),
            )
        )
    attached = scene.attachments if attachments is None else tuple(attachments)
    described = tuple(
        AttachmentDescription(
            a.parent.name, a.parent_link, a.child.name, _frozen(a.parent_link_from_child.matrix())
        )
        for a in attached
    )
    carried = [a for a in attached if a.parent is robot.body]
    carried_names = {a.child.name for a in carried}
    obstacles = [b for b in scene.bodies if b is not robot.body and b.name not in carried_names]
    return SceneDescription(
        bodies=tuple(bodies),
        attachments=described,
        robot=robot.body.name,
        arm_joints=robot.description.arm_joints,
        arm_lower=_frozen(robot.lower),
        arm_upper=_frozen(robot.upper),
        gripper_links=robot.gripper_links,
        checked_pairs=CheckedPairs(robot, obstacles, carried, allowed).policy(),
    )


def describe_collision_checker(
    checker: PyBulletCollisionChecker, urdf_paths: Mapping[str, Path | str] | None = None
) -> SceneDescription:
    """The scene as ``checker`` captured it, with its pairs (the scene is left as it is)."""
    with checker.captured_scene() as attachments:
        return describe_scene(checker.scene, checker.robot, urdf_paths, checker.allowed, attachments)
