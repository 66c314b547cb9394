"""Forward kinematics of a URDF link tree for many configurations at once, with joint frames.

Some joints are variables (the arm's); every other joint is held at the
position given (the fingers, a drawer), fixed joints at zero. ``link_poses``
answers (M, links, 4, 4) world poses for M configurations in a handful of
batched matrix products; ``joint_axes`` gives each variable joint's world axis
and anchor, from which the Jacobian of a point fixed on a link is
``axis x (point - anchor)`` for the revolute joints above the link.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.urdf import UrdfJoint, UrdfModel

FloatArray = npt.NDArray[np.float64]


def _cross_matrix(axis: FloatArray) -> FloatArray:
    x, y, z = axis
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def joint_motion(joint: UrdfJoint, positions: FloatArray) -> FloatArray:
    """(M, 4, 4) motion of ``joint`` at each of ``positions`` (M,), in the joint's frame."""
    count = len(positions)
    motion = np.broadcast_to(np.eye(4), (count, 4, 4)).copy()
    if joint.kind in ("revolute", "continuous"):
        axis = joint.axis / np.linalg.norm(joint.axis)
        cross = _cross_matrix(axis)
        motion[:, :3, :3] += np.sin(positions)[:, None, None] * cross
        motion[:, :3, :3] += (1.0 - np.cos(positions))[:, None, None] * (cross @ cross)
    elif joint.kind == "prismatic":
        motion[:, :3, 3] = positions[:, None] * (joint.axis / np.linalg.norm(joint.axis))
    return motion


@dataclass(frozen=True, eq=False)
class JointAxes:
    """World axes (M, n, 3) and anchors (M, n, 3) of the variable joints; ``revolute`` (n,)."""

    axes: FloatArray
    anchors: FloatArray
    revolute: npt.NDArray[np.bool_]


@dataclass(frozen=True, eq=False)
class TreeLayout:
    """A kinematic tree as arrays (see `sphere_kernels`): root pose, parents (L,), joint origins
    (L, 4, 4), kinds (L,: 0 fixed or held, 1 revolute, 2 prismatic), unit axes (L, 3), the
    configuration column of each variable joint (L,, -1 if none) and held motions (L, 4, 4)."""

    root: FloatArray
    parents: npt.NDArray[np.int64]
    origins: FloatArray
    kinds: npt.NDArray[np.int64]
    axes: FloatArray
    variables: npt.NDArray[np.int64]
    held: FloatArray

    def kernel_arrays(self) -> tuple[Any, ...]:
        """Root, parents, origins with the held motions folded in, kinds, axes, variables: the
        tree as the compiled kernels take it."""
        return (self.root, self.parents, self.origins @ self.held, self.kinds, self.axes, self.variables)


class KinematicTree:
    """A URDF's link tree placed at ``world_from_base``, some joints variable, the rest held."""

    def __init__(
        self,
        model: UrdfModel,
        world_from_base: FloatArray,
        held_positions: Mapping[str, float],
        variable_joints: Sequence[str] = (),
    ) -> None:
        self.model = model
        self.links = model.links
        self.link_index = {name: i for i, name in enumerate(self.links)}
        self.world_from_base = np.asarray(world_from_base, dtype=float)
        self.variable_joints = tuple(variable_joints)
        by_child = {j.child: j for j in model.joints}
        self._joints = [by_child.get(link) for link in self.links]
        self._parents = [-1 if j is None else self.link_index[j.parent] for j in self._joints]
        self._variable = [
            -1 if j is None or j.name not in self.variable_joints else self.variable_joints.index(j.name)
            for j in self._joints
        ]
        self._held = [0.0 if j is None else float(held_positions.get(j.name, 0.0)) for j in self._joints]
        self.revolute = np.array(
            [
                next(j for j in model.joints if j.name == n).kind in ("revolute", "continuous")
                for n in self.variable_joints
            ],
            dtype=bool,
        )
        self.depends = np.zeros((len(self.links), len(self.variable_joints)), dtype=bool)
        """(links, variables): whether a link moves with a variable joint."""
        for link in range(len(self.links)):
            for joint in model.ancestry(self.links[link]):
                if joint.name in self.variable_joints:
                    self.depends[link, self.variable_joints.index(joint.name)] = True

    def _frames(self, qs: FloatArray) -> tuple[FloatArray, FloatArray]:
        """(M, links, 4, 4) link poses and (M, links, 4, 4) joint frames (before the motion)."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        count = len(batch)
        poses = np.empty((count, len(self.links), 4, 4))
        frames = np.empty_like(poses)
        for link, joint in enumerate(self._joints):
            if joint is None:
                poses[:, link] = self.world_from_base
                frames[:, link] = self.world_from_base
                continue
            frames[:, link] = poses[:, self._parents[link]] @ joint.origin
            if joint.kind == "fixed":
                poses[:, link] = frames[:, link]
                continue
            variable = self._variable[link]
            positions = batch[:, variable] if variable >= 0 else np.full(count, self._held[link])
            poses[:, link] = frames[:, link] @ joint_motion(joint, positions)
        return poses, frames

    def flat_layout(self) -> TreeLayout:
        """The tree as arrays, for compiled kernels (held joints folded into ``held``)."""
        count = len(self.links)
        origins, held = (
            np.broadcast_to(np.eye(4), (count, 4, 4)).copy(),
            np.broadcast_to(np.eye(4), (count, 4, 4)).copy(),
        )
        kinds, axes = np.zeros(count, dtype=np.int64), np.zeros((count, 3))
        for link, joint in enumerate(self._joints):
            if joint is None:
                continue
            origins[link] = joint.origin
            if joint.moves:
                axes[link] = joint.axis / np.linalg.norm(joint.axis)
            if self._variable[link] >= 0 and joint.moves:
                kinds[link] = 2 if joint.kind == "prismatic" else 1
            elif joint.moves:
                held[link] = joint_motion(joint, np.array([self._held[link]]))[0]
        return TreeLayout(
            self.world_from_base.copy(),
            np.array(self._parents, dtype=np.int64),
            origins,
            kinds,
            axes,
            np.array(self._variable, dtype=np.int64),
            held,
        )

    def link_poses(self, qs: FloatArray) -> FloatArray:
        """(M, links, 4, 4) world poses of every link for each row of ``qs`` (M, variables)."""
        return self._frames(qs)[0]

    def joint_axes(self, qs: FloatArray) -> tuple[FloatArray, JointAxes]:
        """Link poses and the variable joints' world axes and anchors."""
        poses, frames = self._frames(qs)
        count, variables = len(poses), len(self.variable_joints)
        axes, anchors = np.zeros((count, variables, 3)), np.zeros((count, variables, 3))
        for link, joint in enumerate(self._joints):
            variable = self._variable[link]
            if joint is None or variable < 0:
                continue
            axes[:, variable] = frames[:, link, :3, :3] @ (joint.axis / np.linalg.norm(joint.axis))
            anchors[:, variable] = frames[:, link, :3, 3]
        return poses, JointAxes(axes, anchors, self.revolute)


def point_jacobians(
    points: FloatArray, links: npt.NDArray[np.intp], tree: KinematicTree, frames: JointAxes
) -> FloatArray:
    """(M, P, 3, n) Jacobians of world ``points`` (M, P, 3) fixed on ``links`` (P,) with respect
    to the variable joints."""
    lever = points[:, :, None, :] - frames.anchors[:, None, :, :]  # (M, P, n, 3)
    axes = np.broadcast_to(frames.axes[:, None, :, :], lever.shape)
    rates = np.where(frames.revolute[None, None, :, None], np.cross(axes, lever), axes)
    rates = rates * tree.depends[links][None, :, :, None]
    return np.swapaxes(rates, 2, 3)
