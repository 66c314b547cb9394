"""A scene snapshot as planning-time geometry: the robot (and what it carries) as spheres on its
links, everything else as oriented boxes, and the pairs to check.

Built from the scene description the simulator's checker is described by
(`kitchen_tamp.world.scene_description.SceneDescription`, read through the
`DescribedScene` protocol): every body from its URDF where its base stands,
held joints (the fingers' opening, the drawer) where the description has them.

- Robot links: spheres covering each collision mesh's convex hull, padded by
  ``mesh_padding``; the fingers at their opening. Two coverings of each shape:
  coarse (`sphere_covering`, ``sphere_centers``: a centimetre or two loose,
  what the distance queries use) and tight (`sphere_tight_covering`,
  ``fine_centers``: a few millimetres), which the validity kernel opens only
  where the coarse one cannot clear a pair.
- Carried bodies: their shapes covered by spheres (both levels), riding on the parent link.
- Other bodies: one obstacle shape per collision shape, kept as an oriented box with a kind:
  boxes, spheres and cylinders exactly (a sphere's box is its bounding cube, a cylinder's its
  bounding box along its axis, so code that reads every shape as its box stays conservative);
  meshes by their bounding boxes, which cover them.

Checked pairs follow the description (the same policy as the PyBullet and
Drake checkers): links the arm moves against every obstacle shape except the
allowed contacts; carried shapes against every obstacle and the robot's
non-gripper links; robot links with at least two moving joints between them that the
description lists.
"""

from __future__ import annotations

import functools
import hashlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.described_scene import DescribedScene
from kitchen_tamp.motion.geometry.spheres.covering import (
    DEFAULT_COVERING_TOLERANCE,
    DEFAULT_MAX_SPHERES,
    ConvexPolytope,
    SphereSet,
    box_polytope,
    cover_with_spheres,
    mesh_hull_polytope,
)
from kitchen_tamp.motion.geometry.spheres.kernels.codes import SHAPE_BOX, SHAPE_KINDS
from kitchen_tamp.motion.geometry.spheres.kinematics import KinematicTree
from kitchen_tamp.motion.geometry.spheres.stored_spheres import load_covering, save_covering
from kitchen_tamp.motion.geometry.spheres.tight_covering import TIGHT_COVERING_TOLERANCE, cover_tightly
from kitchen_tamp.motion.geometry.urdf import UrdfCollision, read_urdf

FloatArray = npt.NDArray[np.float64]
IndexArray = npt.NDArray[np.intp]

COVERING_VERSION = "2"
"""Bump when `sphere_covering` changes how spheres are made: cached sphere sets are keyed by it."""
TIGHT_COVERING_VERSION = "tight-1"
"""The same for `sphere_tight_covering`."""
PYBULLET_MESH_MARGIN = 0.001
"""PyBullet pads every convex mesh by about this much (m); robot spheres are padded by it so that
what PyBullet calls touching the model calls touching too."""


def shape_polytope(shape: UrdfCollision) -> ConvexPolytope:
    """A convex polytope covering the shape, in its link's frame."""
    if shape.kind == "mesh":
        local = mesh_hull_polytope(
            shape.mesh_path, (float(shape.size[0]), float(shape.size[1]), float(shape.size[2]))
        )
    elif shape.kind == "box":
        local = box_polytope(shape.size)
    elif shape.kind == "sphere":
        local = box_polytope(np.full(3, 2.0 * shape.size[0]))
    else:  # cylinder along z
        local = box_polytope(np.array([2.0 * shape.size[0], 2.0 * shape.size[0], shape.size[1]]))
    return local.transformed(shape.origin)


def _cache_key(shape: UrdfCollision, tolerance: float, tight: bool) -> str:
    digest = hashlib.sha256()
    digest.update((TIGHT_COVERING_VERSION if tight else COVERING_VERSION).encode())
    digest.update(np.asarray([tolerance, DEFAULT_MAX_SPHERES, *shape.size.tolist()], dtype=float).tobytes())
    digest.update(np.asarray(shape.origin, dtype=float).tobytes())
    digest.update(shape.kind.encode())
    if shape.kind == "mesh":
        digest.update(Path(shape.mesh_path).read_bytes())
    return digest.hexdigest()[:32]


@functools.lru_cache(maxsize=256)
def _covered_shape(urdf_path: str, index: int, tolerance: float, tight: bool = False) -> SphereSet:
    """Spheres covering one collision shape of a URDF, in its link's frame, coarse
    (`cover_with_spheres`) or ``tight`` (`cover_tightly`); kept in memory and stored
    (`stored_spheres`: shipped with the package, else in the user cache): a mesh is covered once
    per machine at most, not once per run."""
    shape = read_urdf(urdf_path).collisions[index]
    if shape.kind == "sphere":
        return SphereSet(shape.origin[:3, 3][None], shape.size[:1].copy())

    def cover() -> SphereSet:
        if tight:
            return cover_tightly(shape_polytope(shape), tolerance)
        return cover_with_spheres(shape_polytope(shape), tolerance)

    key = _cache_key(shape, tolerance, tight)
    stored = load_covering(key)
    if stored is not None:
        return stored
    covered = cover()
    save_covering(key, covered)
    return covered


@dataclass(frozen=True, eq=False)
class SphereGroup:
    """The spheres of one link (``body/link``) or of one carried body's link."""

    name: str
    body: str
    link: str
    robot_link: int
    """Index (in the robot tree) of the link the spheres ride on."""
    spheres: slice
    role: str
    """"moving", "fixed" (a robot link the arm does not move) or "carried"."""
    gripper: bool = False
    fine_spheres: slice = field(default_factory=lambda: slice(0, 0))
    """Where the group's tight covering is in ``SphereScene.fine_centers`` (the fine level)."""


@dataclass(frozen=True, eq=False)
class ObstacleBoxes:
    """Obstacle shapes as oriented boxes: rotations (B, 3, 3) world_from_box, centres (B, 3),
    half extents (B, 3), the (body, link) each belongs to, and each shape's kind (B,)
    (`SHAPE_BOX`; `SHAPE_SPHERE`, half extents its radius thrice; `SHAPE_CYLINDER`, half extents
    radius, radius and half its length, its axis the box's z)."""

    rotations: FloatArray
    centers: FloatArray
    half_extents: FloatArray
    owners: tuple[tuple[str, str], ...]
    kinds: npt.NDArray[np.int64]


def _riding_links(groups: list[SphereGroup], fine: bool) -> IndexArray:
    """Per sphere of one level, the robot link it rides on."""
    ranges = [g.fine_spheres if fine else g.spheres for g in groups]
    counts = [r.stop - r.start for r in ranges]
    return np.repeat(np.array([g.robot_link for g in groups], dtype=np.intp), counts)


class SphereScene:
    """The geometry and the checked pairs of one scene snapshot."""

    def __init__(
        self,
        scene: DescribedScene,
        tolerance: float = DEFAULT_COVERING_TOLERANCE,
        mesh_padding: float = PYBULLET_MESH_MARGIN,
        fine_tolerance: float = TIGHT_COVERING_TOLERANCE,
    ) -> None:
        self.arm_lower: FloatArray = np.array(scene.arm_lower, dtype=float)
        self.arm_upper: FloatArray = np.array(scene.arm_upper, dtype=float)
        robot = next(b for b in scene.bodies if b.name == scene.robot)
        model = read_urdf(robot.urdf_path)
        self.tree = KinematicTree(
            model, robot.world_from_base, robot.joint_positions, tuple(scene.arm_joints)
        )
        carried = {a.child: a for a in scene.attachments if a.parent == scene.robot}
        spheres: list[SphereSet] = []
        fine: list[SphereSet] = []
        groups: list[SphereGroup] = []

        def add(
            name: str, body: str, link: str, robot_link: int, covered: list[SphereSet], role: str
        ) -> None:
            coarse_set, fine_set = SphereSet.concatenate(covered[0::2]), SphereSet.concatenate(covered[1::2])
            start, fine_start = sum(len(s) for s in spheres), sum(len(s) for s in fine)
            spheres.append(coarse_set)
            fine.append(fine_set)
            gripper = role != "carried" and link in scene.gripper_links
            coarse_slice = slice(start, start + len(coarse_set))
            fine_slice = slice(fine_start, fine_start + len(fine_set))
            groups.append(SphereGroup(name, body, link, robot_link, coarse_slice, role, gripper, fine_slice))

        for link in model.links:
            covered = [
                _covered_shape(model.path, i, level_tolerance, tight).padded(
                    mesh_padding if shape.kind == "mesh" else 0.0
                )
                for i, shape in enumerate(model.collisions)
                if shape.link == link
                for level_tolerance, tight in ((tolerance, False), (fine_tolerance, True))
            ]
            if covered:
                index = self.tree.link_index[link]
                role = "moving" if self.tree.depends[index, 0] else "fixed"
                add(f"{scene.robot}/{link}", scene.robot, link, index, covered, role)
        for name, attachment in carried.items():
            body = next(b for b in scene.bodies if b.name == name)
            child = read_urdf(body.urdf_path)
            child_poses = KinematicTree(
                child, attachment.parent_link_from_child, body.joint_positions
            ).link_poses(np.zeros((1, 0)))[0]
            for link in child.links:
                covered = [
                    _covered_shape(child.path, i, level_tolerance, tight).transformed(
                        child_poses[child.links.index(link)]
                    )
                    for i, shape in enumerate(child.collisions)
                    if shape.link == link
                    for level_tolerance, tight in ((tolerance, False), (fine_tolerance, True))
                ]
                if covered:
                    parent_index = self.tree.link_index[attachment.parent_link]
                    add(f"{name}/{link}", name, link, parent_index, covered, "carried")
        merged = SphereSet.concatenate(spheres)
        self.sphere_centers: FloatArray = merged.centers
        """(S, 3) sphere centres in the frame of the robot link each rides on."""
        self.sphere_radii: FloatArray = merged.radii
        self.sphere_links: IndexArray = _riding_links(groups, fine=False)
        merged_fine = SphereSet.concatenate(fine)
        self.fine_centers: FloatArray = merged_fine.centers
        """(F, 3) the tight covering's sphere centres (the fine level), as ``sphere_centers``."""
        self.fine_radii: FloatArray = merged_fine.radii
        self.fine_links: IndexArray = _riding_links(groups, fine=True)
        self.groups = tuple(groups)
        self.boxes = self._obstacle_boxes(scene, set(carried))
        self.group_box_pairs, self.group_pairs = self._checked_pairs(scene)

    @staticmethod
    def _obstacle_boxes(scene: DescribedScene, carried: set[str]) -> ObstacleBoxes:
        poses, halves, owners, kinds = [], [], [], []
        world_from: dict[str, FloatArray] = {}
        for body in scene.bodies:
            if body.name == scene.robot or body.name in carried:
                continue
            model = read_urdf(body.urdf_path)
            base = np.asarray(body.world_from_base, dtype=float)
            attachment = next((a for a in scene.attachments if a.child == body.name), None)
            if attachment is not None and attachment.parent in world_from:
                base = world_from[attachment.parent] @ attachment.parent_link_from_child
            link_poses = KinematicTree(model, base, body.joint_positions).link_poses(np.zeros((1, 0)))[0]
            world_from[body.name] = link_poses[0]
            for shape in model.collisions:
                kinds.append(SHAPE_KINDS.get(shape.kind, SHAPE_BOX))
                if shape.kind == "box":
                    local_pose, half = shape.origin, shape.size / 2.0
                elif shape.kind == "sphere":
                    local_pose, half = shape.origin, np.full(3, shape.size[0])
                elif shape.kind == "cylinder":
                    local_pose, half = shape.origin, shape.size[[0, 0, 1]] * [1.0, 1.0, 0.5]
                else:  # a mesh: the box around its hull
                    vertices = shape_polytope(shape).vertices
                    local_pose = np.eye(4)
                    local_pose[:3, 3] = (vertices.min(axis=0) + vertices.max(axis=0)) / 2.0
                    half = (vertices.max(axis=0) - vertices.min(axis=0)) / 2.0
                poses.append(link_poses[model.links.index(shape.link)] @ local_pose)
                halves.append(half)
                owners.append((body.name, shape.link))
        stacked = np.array(poses).reshape(-1, 4, 4)
        return ObstacleBoxes(
            stacked[:, :3, :3].copy(),
            stacked[:, :3, 3].copy(),
            np.array(halves).reshape(-1, 3),
            tuple(owners),
            np.array(kinds, dtype=np.int64),
        )

    def _checked_pairs(self, scene: DescribedScene) -> tuple[IndexArray, IndexArray]:
        """(group, box) pairs and (group, group) pairs that are checked."""
        tree_model = self.tree.model
        # The robot's side of the described pair table (kitchen_tamp.world.collision.checked_pairs); an
        # intended contact's pair is kept too (spheres then defer it to the exact model). A self
        # pair is checked when the description lists it and two moving joints part its links.
        pairs = scene.checked_pairs
        robot_pairs = {(p.link_a, p.body_b, p.link_b) for p in pairs if p.body_a == scene.robot}
        robot_pairs |= {(p.link_b, p.body_a, p.link_a) for p in pairs if p.body_b == scene.robot}
        robot = scene.robot
        box_pairs, group_pairs = [], []
        for g, group in enumerate(self.groups):
            for b, (body, link) in enumerate(self.boxes.owners):
                if group.role == "carried" or (
                    group.role == "moving" and (group.link, body, link) in robot_pairs
                ):
                    box_pairs.append((g, b))
            for h in range(g + 1, len(self.groups)):
                other = self.groups[h]
                carried_pair = {group.role, other.role} & {"carried"}
                if carried_pair:
                    robot_side = other if group.role == "carried" else group
                    if robot_side.role != "carried" and not robot_side.gripper:
                        group_pairs.append((g, h))
                elif (
                    tree_model.moving_joints_between(group.link, other.link) >= 2
                    and (group.link, robot, other.link) in robot_pairs
                ):
                    group_pairs.append((g, h))
        return np.array(box_pairs, dtype=np.intp).reshape(-1, 2), np.array(
            group_pairs, dtype=np.intp
        ).reshape(-1, 2)

    def sphere_positions(self, link_poses: FloatArray) -> FloatArray:
        """(M, S, 3) world sphere centres from (M, links, 4, 4) link poses."""
        poses = link_poses[:, self.sphere_links]
        rotated: FloatArray = np.einsum("mskl,sl->msk", poses[:, :, :3, :3], self.sphere_centers)
        return rotated + poses[:, :, :3, 3]
