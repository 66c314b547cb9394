"""A loaded URDF body whose links and joints are looked up by name."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Final

import numpy as np
import pybullet as p

from kitchen_tamp.world.errors import UnknownNameError
from kitchen_tamp.world.transforms import FloatArray, Pose

BASE_LINK: Final = -1
"""PyBullet's index of a body's base link."""


@dataclass(frozen=True)
class JointInfo:
    """What the URDF says about one joint."""

    name: str
    index: int
    child_link: str
    parent_index: int
    movable: bool
    revolute: bool
    fixed: bool
    """A fixed joint: its child link never moves relative to its parent."""
    lower: float
    upper: float


@dataclass(frozen=True)
class BoxShape:
    """One box collision primitive of a link, in the link's centre-of-mass frame."""

    com_from_box: Pose
    size: tuple[float, float, float]


class Body:
    """A body in one physics client, with name lookup for its links and joints."""

    def __init__(self, client: int, uid: int, name: str) -> None:
        self.client = client
        self.uid = uid
        self.name = name
        joints = [p.getJointInfo(uid, j, physicsClientId=client) for j in range(self._num_joints())]
        base_name: str = p.getBodyInfo(uid, physicsClientId=client)[0].decode()
        self.base_link_name: str = base_name
        self.joints: tuple[JointInfo, ...] = tuple(
            JointInfo(
                name=info[1].decode(),
                index=info[0],
                child_link=info[12].decode(),
                parent_index=info[16],
                movable=info[2] in (p.JOINT_REVOLUTE, p.JOINT_PRISMATIC),
                revolute=info[2] == p.JOINT_REVOLUTE,
                fixed=info[2] == p.JOINT_FIXED,
                lower=float(info[8]),
                upper=float(info[9]),
            )
            for info in joints
        )
        self._link_index: dict[str, int] = {base_name: BASE_LINK} | {
            j.child_link: j.index for j in self.joints
        }
        self._link_name = {index: name for name, index in self._link_index.items()}
        self._joint_by_name = {j.name: j for j in self.joints}
        dynamics = p.getDynamicsInfo(uid, BASE_LINK, physicsClientId=client)
        self._base_from_com = Pose.from_parts(dynamics[3], dynamics[4])
        self._com_from_base = self._base_from_com.inverse()

    def _num_joints(self) -> int:
        return int(p.getNumJoints(self.uid, physicsClientId=self.client))

    def __repr__(self) -> str:
        return f"Body({self.name!r}, uid={self.uid})"

    @property
    def link_names(self) -> tuple[str, ...]:
        """Every link name, base first."""
        return tuple(self._link_index)

    @property
    def link_indices(self) -> tuple[int, ...]:
        """Every link index, base (-1) first."""
        return tuple(self._link_index.values())

    def link_index(self, link: str) -> int:
        """PyBullet's index of the link called ``link``."""
        try:
            return self._link_index[link]
        except KeyError:
            raise UnknownNameError(f"body {self.name!r} has no link {link!r}") from None

    def link_name(self, index: int) -> str:
        """The name of the link with PyBullet index ``index``."""
        try:
            return self._link_name[index]
        except KeyError:
            raise UnknownNameError(f"body {self.name!r} has no link index {index}") from None

    def welded_links(self) -> frozenset[int]:
        """The links joined to the base by fixed joints only, and the base (for a fixed-base body,
        the links that cannot move)."""
        welded = {BASE_LINK}
        for joint in self.joints:  # PyBullet lists a parent's joint before its children's
            if joint.fixed and joint.parent_index in welded:
                welded.add(joint.index)
        return frozenset(welded)

    def joint(self, name: str) -> JointInfo:
        """The joint called ``name``."""
        try:
            return self._joint_by_name[name]
        except KeyError:
            raise UnknownNameError(f"body {self.name!r} has no joint {name!r}") from None

    def joint_indices(self, names: Sequence[str]) -> tuple[int, ...]:
        """PyBullet indices of the named joints, in the given order."""
        return tuple(self.joint(n).index for n in names)

    def joint_positions(self, names: Sequence[str]) -> FloatArray:
        """Current positions of the named joints."""
        states = p.getJointStates(self.uid, self.joint_indices(names), physicsClientId=self.client)
        return np.array([s[0] for s in states], dtype=float)

    def reset_joint_positions(self, names: Sequence[str], values: Sequence[float]) -> None:
        """Teleport the named joints (no attachment update: use ``Scene.set_joint_positions``)."""
        for index, value in zip(self.joint_indices(names), values, strict=True):
            p.resetJointState(self.uid, index, float(value), physicsClientId=self.client)

    def base_pose(self) -> Pose:
        """``world_from_base`` of the base link's URDF frame (not its inertial frame)."""
        return self._world_from_base_com() @ self._base_from_com.inverse()

    def _world_from_base_com(self) -> Pose:
        position, quaternion = p.getBasePositionAndOrientation(self.uid, physicsClientId=self.client)
        return Pose.from_parts(position, quaternion)

    def reset_base_pose(self, world_from_base: Pose) -> None:
        """Teleport the body so that its base link's URDF frame is at ``world_from_base``."""
        world_from_com = world_from_base @ self._base_from_com
        p.resetBasePositionAndOrientation(
            self.uid, world_from_com.position, world_from_com.quaternion, physicsClientId=self.client
        )

    def link_pose(self, link: str) -> Pose:
        """``world_from_link`` of the named link's URDF frame."""
        index = self.link_index(link)
        if index == BASE_LINK:
            return self.base_pose()
        state = p.getLinkState(self.uid, index, computeForwardKinematics=True, physicsClientId=self.client)
        return Pose.from_parts(state[4], state[5])

    def link_frames(self, links: Sequence[str]) -> tuple[FloatArray, FloatArray]:
        """World positions (n, 3) and quaternions (n, 4; x, y, z, w) of the named links' URDF
        frames, read in one call (for recording many frames; ``link_pose`` for one pose)."""
        indices = [self.link_index(link) for link in links]
        positions = np.zeros((len(indices), 3))
        quaternions = np.zeros((len(indices), 4))
        moving = [i for i, index in enumerate(indices) if index != BASE_LINK]
        if moving:
            states = p.getLinkStates(
                self.uid,
                [indices[i] for i in moving],
                computeForwardKinematics=True,
                physicsClientId=self.client,
            )
            for i, state in zip(moving, states, strict=True):
                positions[i], quaternions[i] = state[4], state[5]
        if len(moving) < len(indices):
            world_from_com = p.getBasePositionAndOrientation(self.uid, physicsClientId=self.client)
            com_from_base = self._com_from_base
            base = p.multiplyTransforms(*world_from_com, com_from_base.position, com_from_base.quaternion)
            for i, index in enumerate(indices):
                if index == BASE_LINK:
                    positions[i], quaternions[i] = base
        return positions, quaternions

    def link_com_pose(self, link: str) -> Pose:
        """``world_from_com`` of the named link (the frame its collision shapes are given in)."""
        index = self.link_index(link)
        if index == BASE_LINK:
            return self._world_from_base_com()
        state = p.getLinkState(self.uid, index, computeForwardKinematics=True, physicsClientId=self.client)
        return Pose.from_parts(state[0], state[1])

    def box_shapes(self, link: str) -> tuple[BoxShape, ...]:
        """The box collision primitives of a link, as written in its URDF."""
        index = self.link_index(link)
        shapes = p.getCollisionShapeData(self.uid, index, physicsClientId=self.client)
        return tuple(
            BoxShape(Pose.from_parts(s[5], s[6]), (float(s[3][0]), float(s[3][1]), float(s[3][2])))
            for s in shapes
            if s[2] == p.GEOM_BOX
        )

    def aabb(self, link: str | None = None) -> tuple[FloatArray, FloatArray]:
        """Axis-aligned bounds (lower, upper) of one link, or of the whole body."""
        indices = self.link_indices if link is None else (self.link_index(link),)
        lows, highs = [], []
        for index in indices:
            low, high = p.getAABB(self.uid, index, physicsClientId=self.client)
            lows.append(low)
            highs.append(high)
        return np.min(np.array(lows), axis=0), np.max(np.array(highs), axis=0)
