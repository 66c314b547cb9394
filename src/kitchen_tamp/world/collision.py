"""Collision checking of arm configurations against a frozen snapshot of the scene.

A ``CollisionChecker`` is the only thing a motion planner needs from the world:
``is_valid`` over a batch of configurations, ``segment_valid`` between two of
them, the joint limits, and ``min_clearance`` for verification. It captures the
scene when it is made (what the arm carries, where the drawer is), so it stays
right even if the scene changes later, and it always leaves the scene as it
found it.

Checked: every moving robot link against every other body; every body the robot
carries against every other body and the robot's non-gripper links; robot links
against each other when at least two movable joints separate them (links joined
by one joint touch by construction).
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np
import pybullet as p
from numpy.typing import NDArray

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import BASE_LINK, Body
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray

BoolArray = NDArray[np.bool_]

CLEARANCE_HORIZON = 0.5
"""Distance (m) beyond which ``min_clearance`` stops looking and reports this value."""


@dataclass(frozen=True)
class AllowedContact:
    """Robot links (all when None) that may touch ``body``'s link (all links when None).

    Used for intended contact: the fingers around the box being grasped, the
    gripper on the drawer handle.
    """

    body: str
    link: str | None = None
    robot_links: frozenset[str] | None = None

    def allows(self, robot_link: str, body: str, link: str) -> bool:
        """Whether this contact covers ``robot_link`` touching ``body``'s ``link``."""
        return (
            body == self.body
            and (self.link is None or self.link == link)
            and (self.robot_links is None or robot_link in self.robot_links)
        )


def _movable_joints_between(body: Body, link_a: int, link_b: int) -> int:
    """Number of movable joints on the kinematic chain joining two links of a body."""
    parents = {j.index: (j.parent_index, j.movable) for j in body.joints}

    def ancestry(link: int) -> list[tuple[int, bool]]:
        chain = []
        while link != BASE_LINK:
            parent, movable = parents[link]
            chain.append((link, movable))
            link = parent
        return chain

    chain_a, chain_b = ancestry(link_a), ancestry(link_b)
    links_a = {lnk for lnk, _ in chain_a}
    links_b = {lnk for lnk, _ in chain_b}
    shared = links_a & links_b
    return sum(m for lnk, m in chain_a if lnk not in shared) + sum(
        m for lnk, m in chain_b if lnk not in shared
    )


@functools.lru_cache(maxsize=16)
def _robot_link_sets(body: Body, first_arm_joint: str) -> tuple[frozenset[int], tuple[tuple[int, int], ...]]:
    """(links moved by the arm, self-collision pairs with >= 2 movable joints between them)."""
    parents = {j.index: j.parent_index for j in body.joints}
    root = body.joint(first_arm_joint).index

    def moves(link: int) -> bool:
        while link != BASE_LINK:
            if link == root:
                return True
            link = parents[link]
        return False

    moving = frozenset(i for i in body.link_indices if moves(i))
    geometric = [
        i for i in body.link_indices if p.getCollisionShapeData(body.uid, i, physicsClientId=body.client)
    ]
    pairs = tuple(
        (a, b) for a, b in itertools.combinations(geometric, 2) if _movable_joints_between(body, a, b) >= 2
    )
    return moving, pairs


class CollisionChecker:
    """Batch collision checks of arm configurations in a snapshot of a scene."""

    def __init__(
        self,
        scene: Scene,
        robot: Robot,
        allowed: Iterable[AllowedContact] = (),
        margin: float = 0.0,
    ) -> None:
        self.scene = scene
        self.robot = robot
        self.margin = float(margin)
        self.allowed: tuple[AllowedContact, ...] = tuple(allowed)
        self.lower: FloatArray = robot.lower.copy()
        self.upper: FloatArray = robot.upper.copy()
        self._snapshot = scene.save_state()
        self.carried: tuple[Attachment, ...] = tuple(a for a in scene.attachments if a.parent is robot.body)
        carried_names = {a.child.name for a in self.carried}
        self.obstacles: tuple[Body, ...] = tuple(
            b for b in scene.bodies if b is not robot.body and b.name not in carried_names
        )
        self._moving_links, self._self_pairs = _robot_link_sets(robot.body, robot.description.arm_joints[0])
        self._gripper_indices = frozenset(robot.body.link_index(n) for n in robot.gripper_links)

    # -- one configuration ---------------------------------------------------------------------
    def _place(self, q: FloatArray) -> None:
        self.robot.body.reset_joint_positions(self.robot.description.arm_joints, list(q))
        for attachment in self.carried:
            attachment.apply()

    def _is_allowed(self, robot_link: int, other: Body, other_link: int) -> bool:
        if not self.allowed:
            return False
        robot_name = self.robot.body.link_name(robot_link)
        other_name = other.link_name(other_link)
        return any(a.allows(robot_name, other.name, other_name) for a in self.allowed)

    def _distances(self, horizon: float) -> Iterator[float]:
        """Signed distances (within ``horizon``) of every checked pair at the current state."""
        robot = self.robot.body
        client = robot.client
        for obstacle in self.obstacles:
            for point in p.getClosestPoints(robot.uid, obstacle.uid, horizon, physicsClientId=client):
                if point[3] in self._moving_links and not self._is_allowed(point[3], obstacle, point[4]):
                    yield float(point[8])
        for attachment in self.carried:
            child = attachment.child
            for obstacle in self.obstacles:
                for point in p.getClosestPoints(child.uid, obstacle.uid, horizon, physicsClientId=client):
                    yield float(point[8])
            for point in p.getClosestPoints(child.uid, robot.uid, horizon, physicsClientId=client):
                if point[4] not in self._gripper_indices:
                    yield float(point[8])
        for a, b in self._self_pairs:
            for point in p.getClosestPoints(robot.uid, robot.uid, horizon, a, b, physicsClientId=client):
                yield float(point[8])

    def _collides_here(self) -> bool:
        return any(d < self.margin for d in self._distances(max(self.margin, 0.0)))

    def _clearance_here(self) -> float:
        return min(self._distances(CLEARANCE_HORIZON), default=CLEARANCE_HORIZON)

    # -- public batch interface ------------------------------------------------------------------
    def is_valid(self, qs: FloatArray) -> BoolArray:
        """For each row of ``qs`` (n, dof): within limits and collision-free."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = np.zeros(len(batch), dtype=bool)
        with self.scene.preserved():
            self.scene.restore_state(self._snapshot)
            for i, q in enumerate(batch):
                if not self.robot.within_limits(q):
                    continue
                self._place(q)
                valid[i] = not self._collides_here()
        return valid

    def is_valid_along(
        self, qs: FloatArray, body: Body, joint_names: Sequence[str], joint_values: FloatArray
    ) -> BoolArray:
        """Like ``is_valid`` while ``body``'s joints take ``joint_values[i]`` at ``qs[i]``
        (e.g. a drawer pulled by the hand); bodies attached to them follow."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        values = np.asarray(joint_values, dtype=float).reshape(len(batch), -1)
        valid = np.zeros(len(batch), dtype=bool)
        with self.scene.preserved():
            self.scene.restore_state(self._snapshot)
            for i, q in enumerate(batch):
                if not self.robot.within_limits(q):
                    continue
                self.scene.set_joint_positions(body, joint_names, list(values[i]))
                self._place(q)
                valid[i] = not self._collides_here()
        return valid

    def in_collision(self, q: FloatArray) -> bool:
        """Whether one configuration collides (or violates a limit)."""
        return not bool(self.is_valid(np.asarray(q, dtype=float)[None, :])[0])

    def segment_valid(self, q0: FloatArray, q1: FloatArray, resolution_rad: float = 0.01) -> bool:
        """Whether the straight joint-space segment is valid at ``resolution_rad`` spacing.

        The endpoints are checked first, then the interior coarse-to-fine, so a
        blocked segment usually fails after a few checks.
        """
        start, end = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
        if not bool(np.all(self.is_valid(np.stack([start, end])))):
            return False
        steps = int(np.ceil(float(np.max(np.abs(end - start))) / resolution_rad))
        if steps <= 1:
            return True
        order = _coarse_to_fine(steps)
        fractions = np.array(order, dtype=float) / steps
        interior = start + fractions[:, None] * (end - start)
        with self.scene.preserved():
            self.scene.restore_state(self._snapshot)
            for q in interior:
                self._place(q)
                if self._collides_here():
                    return False
        return True

    def min_clearance(self, qs: FloatArray) -> FloatArray:
        """Smallest signed distance (m, negative when penetrating) per configuration,
        capped at ``CLEARANCE_HORIZON``; allowed contacts are left out."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        clearances = np.empty(len(batch))
        with self.scene.preserved():
            self.scene.restore_state(self._snapshot)
            for i, q in enumerate(batch):
                self._place(q)
                clearances[i] = self._clearance_here()
        return clearances

    def colliding_pairs(self, q: FloatArray) -> list[tuple[str, str]]:
        """Human-readable names of the pairs in collision at ``q`` (for error messages)."""
        pairs: list[tuple[str, str]] = []
        robot = self.robot.body
        with self.scene.preserved():
            self.scene.restore_state(self._snapshot)
            self._place(np.asarray(q, dtype=float))
            for obstacle in self.obstacles:
                for pt in p.getClosestPoints(robot.uid, obstacle.uid, 0.0, physicsClientId=robot.client):
                    if (
                        pt[8] < self.margin
                        and pt[3] in self._moving_links
                        and not self._is_allowed(pt[3], obstacle, pt[4])
                    ):
                        pairs.append((robot.link_name(pt[3]), f"{obstacle.name}/{obstacle.link_name(pt[4])}"))
            for attachment in self.carried:
                for other in (*self.obstacles, robot):
                    for pt in p.getClosestPoints(
                        attachment.child.uid, other.uid, 0.0, physicsClientId=robot.client
                    ):
                        if pt[8] < self.margin and not (other is robot and pt[4] in self._gripper_indices):
                            pairs.append((attachment.child.name, f"{other.name}/{other.link_name(pt[4])}"))
            for a, b in self._self_pairs:
                for pt in p.getClosestPoints(robot.uid, robot.uid, 0.0, a, b, physicsClientId=robot.client):
                    if pt[8] < self.margin:
                        pairs.append((robot.link_name(a), robot.link_name(b)))
        return sorted(set(pairs))


def _coarse_to_fine(steps: int) -> list[int]:
    """Interior indices 1..steps-1 ordered by bisection (midpoint first)."""
    order: list[int] = []
    seen = {0, steps}
    intervals = [(0, steps)]
    while intervals:
        next_intervals = []
        for lo, hi in intervals:
            if hi - lo < 2:
                continue
            mid = (lo + hi) // 2
            if mid not in seen:
                seen.add(mid)
                order.append(mid)
            next_intervals += [(lo, mid), (mid, hi)]
        intervals = next_intervals
    return order


def make_collision_checker(
    scene: Scene, robot: Robot, allowed: Iterable[AllowedContact] = (), margin: float = 0.0
) -> CollisionChecker:
    """The factory motion planners are given: a checker of the scene as it is now."""
    return CollisionChecker(scene, robot, allowed, margin)
