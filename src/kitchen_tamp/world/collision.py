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

Speed (tens of microseconds per configuration): the pairs are listed once, link
by link, without the allowed contacts. Per configuration the moving links'
axis-aligned bounds are read (``getAABB`` is exact and current after a joint
reset) and only the pairs whose bounds come within the query distance go to
``getClosestPoints`` (bounds ``g`` apart mean shapes at least ``g`` apart), the
most overlapping first, stopping at the first collision. The scene is saved and
restored as raw PyBullet values rather than ``Pose`` objects.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
import pybullet as p
from numpy.typing import NDArray

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import BASE_LINK, Body
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray, Pose

BoolArray = NDArray[np.bool_]

CLEARANCE_HORIZON = 0.5
"""Distance (m) beyond which ``min_clearance`` stops looking and reports this value."""

BOUNDS_SLACK = 1e-6
"""Pairs whose bounds are within the query distance plus this (m) are measured exactly."""

STATE_TOLERANCE = 1e-12
"""Scene states this close count as the snapshot (PyBullet echoes orientations to an ulp)."""

RawBodyState = tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]
"""A body's centre-of-mass position and quaternion and its movable joints' positions."""

_flatten = itertools.chain.from_iterable


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


def _ancestry(body: Body, link: int) -> list[tuple[int, bool]]:
    """(link, whether its joint is movable) from ``link`` up to the base, base excluded."""
    parents = {j.index: (j.parent_index, j.movable) for j in body.joints}
    chain = []
    while link != BASE_LINK:
        parent, movable = parents[link]
        chain.append((link, movable))
        link = parent
    return chain


def _movable_joints_between(body: Body, link_a: int, link_b: int) -> int:
    """Number of movable joints on the kinematic chain joining two links of a body."""
    chain_a, chain_b = _ancestry(body, link_a), _ancestry(body, link_b)
    shared = {lnk for lnk, _ in chain_a} & {lnk for lnk, _ in chain_b}
    return sum(movable for lnk, movable in chain_a + chain_b if lnk not in shared)


@functools.lru_cache(maxsize=64)
def _collision_links(body: Body) -> tuple[int, ...]:
    """Indices of the links of ``body`` that have collision shapes."""
    client = body.client
    return tuple(i for i in body.link_indices if p.getCollisionShapeData(body.uid, i, physicsClientId=client))


@functools.lru_cache(maxsize=16)
def _robot_link_sets(body: Body, first_arm_joint: str) -> tuple[frozenset[int], tuple[tuple[int, int], ...]]:
    """(links moved by the arm, self-collision pairs with >= 2 movable joints between them)."""
    root = body.joint(first_arm_joint).index
    moving = frozenset(i for i in body.link_indices if any(lnk == root for lnk, _ in _ancestry(body, i)))
    pairs = itertools.combinations(_collision_links(body), 2)
    return moving, tuple((a, b) for a, b in pairs if _movable_joints_between(body, a, b) >= 2)


def _in_dependency_order(attachments: Sequence[Attachment]) -> tuple[Attachment, ...]:
    """Attachments ordered parents first, as ``Scene.update_attachments`` applies them."""
    ordered: list[Attachment] = []
    pending = list(attachments)
    while pending:
        children = {a.child.name for a in pending}
        ready = [a for a in pending if a.parent.name not in children] or pending
        ordered += ready
        pending = [a for a in pending if a not in ready]
    return tuple(ordered)


def _nearly_equal(a: tuple[RawBodyState, ...], b: tuple[RawBodyState, ...]) -> bool:
    flat_a = np.fromiter(_flatten(_flatten(a)), dtype=float)
    flat_b = np.fromiter(_flatten(_flatten(b)), dtype=float)
    return len(flat_a) == len(flat_b) and bool(np.max(np.abs(flat_a - flat_b)) <= STATE_TOLERANCE)


class _CarriedPlacement:
    """Moves a carried body with its parent link, in raw PyBullet transforms when it can."""

    def __init__(self, attachment: Attachment) -> None:
        parent, child = attachment.parent, attachment.child
        self.attachment = attachment
        self.client, self.parent_uid, self.child_uid = parent.client, parent.uid, child.uid
        self.link = parent.link_index(attachment.parent_link)
        child_com = Pose.from_parts(*p.getBasePositionAndOrientation(child.uid, physicsClientId=self.client))
        offset = attachment.parent_link_from_child @ child.base_pose().inverse() @ child_com
        self.offset = (offset.position, offset.quaternion)

    def apply(self) -> None:
        """Put the child where its parent link now says."""
        if self.link == BASE_LINK:
            self.attachment.apply()
            return
        link = p.getLinkState(
            self.parent_uid, self.link, computeForwardKinematics=True, physicsClientId=self.client
        )
        world = p.multiplyTransforms(link[4], link[5], *self.offset)
        p.resetBasePositionAndOrientation(self.child_uid, world[0], world[1], physicsClientId=self.client)


Along = tuple[Body, Sequence[str], FloatArray]
"""A body whose named joints take the i-th row of the values at the i-th configuration."""


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
        self._limits = (self.lower - 1e-9, self.upper + 1e-9)  # as Robot.within_limits
        self.carried: tuple[Attachment, ...] = tuple(a for a in scene.attachments if a.parent is robot.body)
        carried_names = {a.child.name for a in self.carried}
        self.obstacles: tuple[Body, ...] = tuple(
            b for b in scene.bodies if b is not robot.body and b.name not in carried_names
        )
        self._client = robot.body.client
        self._bodies = scene.bodies
        self._joints = tuple(tuple(j.index for j in b.joints if j.movable) for b in self._bodies)
        self._snapshot = self._read_state()
        self._attachments = _in_dependency_order(scene.attachments)
        self._placements = tuple(_CarriedPlacement(a) for a in self.carried)
        self._arm = robot.body.joint_indices(robot.description.arm_joints)
        self._robot_slot = self._bodies.index(robot.body)
        self._arm_in_robot_state = [self._joints[self._robot_slot].index(i) for i in self._arm]
        self._carried_slots = tuple(self._bodies.index(a.child) for a in self.carried)
        self._build_pairs()
        self._static_bounds = self._bounds(self._static_rows)

    # -- pair table ------------------------------------------------------------------------------
    def _build_pairs(self) -> None:
        """Rows (body, link) whose bounds are read, and the checked pairs of rows."""
        robot = self.robot.body
        moving, self_pairs = _robot_link_sets(robot, self.robot.description.arm_joints[0])
        gripper = {robot.link_index(n) for n in self.robot.gripper_links}
        robot_links = _collision_links(robot)
        obstacle_links = [(o, b) for o in self.obstacles for b in _collision_links(o)]
        moving_rows = [(robot, i) for i in robot_links if i in moving]
        moving_rows += [(a.child, i) for a in self.carried for i in _collision_links(a.child)]
        static_rows = [(robot, i) for i in robot_links if i not in moving] + obstacle_links
        pairs = [
            (robot, a, o, b)
            for a in robot_links
            if a in moving
            for o, b in obstacle_links
            if not self._is_allowed(a, o, b)
        ]
        for child in (a.child for a in self.carried):
            for c in _collision_links(child):
                pairs += [(child, c, o, b) for o, b in obstacle_links]
                pairs += [(child, c, robot, b) for b in robot_links if b not in gripper]
        pairs += [(robot, a, robot, b) for a, b in self_pairs]
        self._moving_rows = tuple((b.uid, i) for b, i in moving_rows)
        self._static_rows = tuple((b.uid, i) for b, i in static_rows)
        self._pairs = tuple(pairs)
        self._pair_ids = [(a.uid, i, b.uid, j) for a, i, b, j in pairs]
        # Bounds are a flat table of (low xyz, high xyz) rows. Per pair and axis,
        # low_a - high_b and low_b - high_a: the largest of the six is the gap.
        row_of = {(b.name, i): r for r, (b, i) in enumerate(moving_rows + static_rows)}
        rows_a = 6 * np.array([row_of[a.name, i] for a, i, _, _ in pairs], dtype=np.intp)[:, None]
        rows_b = 6 * np.array([row_of[b.name, j] for _, _, b, j in pairs], dtype=np.intp)[:, None]
        axes = np.arange(3)
        self._gap_minuends = np.hstack([rows_a + axes, rows_b + axes]).T.reshape(-1)
        self._gap_subtrahends = np.hstack([rows_b + 3 + axes, rows_a + 3 + axes]).T.reshape(-1)

    def _is_allowed(self, robot_link: int, other: Body, other_link: int) -> bool:
        robot_name, other_name = self.robot.body.link_name(robot_link), other.link_name(other_link)
        return any(a.allows(robot_name, other.name, other_name) for a in self.allowed)

    def _bounds(self, rows: Sequence[tuple[int, int]]) -> FloatArray:
        """Current axis-aligned bounds of the rows' links, flat: (low xyz, high xyz) per row."""
        boxes = [p.getAABB(uid, link, physicsClientId=self._client) for uid, link in rows]
        return np.fromiter(_flatten(_flatten(boxes)), dtype=float, count=6 * len(rows))

    def _candidates(self, horizon: float, static_bounds: FloatArray) -> list[tuple[int, float]]:
        """(pair, gap between its bounds) for the pairs whose bounds come within ``horizon``,
        the most overlapping first."""
        table = np.concatenate([self._bounds(self._moving_rows), static_bounds])
        gaps = (table.take(self._gap_minuends) - table.take(self._gap_subtrahends)).reshape(6, -1).max(axis=0)
        near = np.flatnonzero(gaps <= horizon + BOUNDS_SLACK)
        near = near[np.argsort(gaps[near], kind="stable")]
        return list(zip(near.tolist(), gaps[near].tolist(), strict=True))

    # -- scene state ------------------------------------------------------------------------------
    def _read_state(self) -> tuple[RawBodyState, ...]:
        client = self._client
        states = []
        for body, joints in zip(self._bodies, self._joints, strict=True):
            position, orientation = p.getBasePositionAndOrientation(body.uid, physicsClientId=client)
            values = p.getJointStates(body.uid, joints, physicsClientId=client) if joints else ()
            states.append((position, orientation, tuple(v[0] for v in values)))
        return tuple(states)

    def _write_state(self, state: tuple[RawBodyState, ...], slots: Iterable[int]) -> None:
        client = self._client
        for slot in slots:
            uid, joints = self._bodies[slot].uid, self._joints[slot]
            position, orientation, values = state[slot]
            p.resetBasePositionAndOrientation(uid, position, orientation, physicsClientId=client)
            if joints:
                p.resetJointStatesMultiDof(uid, joints, [[v] for v in values], physicsClientId=client)

    @contextmanager
    def _in_snapshot(self, only_arm_moves: bool) -> Iterator[None]:
        """The scene as it was when the checker was made; afterwards as the caller had it
        (putting back only the arm and what it carries when nothing else moved)."""
        found = self._read_state()
        unchanged = found == self._snapshot or _nearly_equal(found, self._snapshot)
        if not unchanged:
            self._write_state(self._snapshot, range(len(self._bodies)))
        try:
            yield
        finally:
            if unchanged and only_arm_moves:
                self._write_state(found, self._carried_slots)
                arm = [[found[self._robot_slot][2][k]] for k in self._arm_in_robot_state]
                p.resetJointStatesMultiDof(self.robot.body.uid, self._arm, arm, physicsClientId=self._client)
            else:
                self._write_state(found, range(len(self._bodies)))

    @contextmanager
    def captured_scene(self) -> Iterator[tuple[Attachment, ...]]:
        """Within: the scene posed as when the checker was made; yields the attachments it had
        then (the scene's own attachment list is not changed). Everything is put back after."""
        with self._in_snapshot(only_arm_moves=False):
            yield self._attachments

    # -- one configuration ---------------------------------------------------------------------
    def _place(self, q: FloatArray, along: Along | None = None, row: int = 0) -> FloatArray:
        """Arm (and what it carries) at ``q``, ``along``'s joints at their ``row``; the obstacles' bounds."""
        static_bounds = self._static_bounds
        if along is not None:
            body, joint_names, values = along
            body.reset_joint_positions(joint_names, list(values[row]))
            for attachment in self._attachments:
                attachment.apply()
        uid, client = self.robot.body.uid, self._client
        p.resetJointStatesMultiDof(uid, self._arm, [[float(v)] for v in q], physicsClientId=client)
        for placement in self._placements:
            placement.apply()
        return static_bounds if along is None else self._bounds(self._static_rows)

    def _distances(self, horizon: float, static_bounds: FloatArray) -> Iterator[float]:
        """Signed distances (within ``horizon``) of the checked pairs at the current state."""
        client = self._client
        for k, _ in self._candidates(horizon, static_bounds):
            uid_a, link_a, uid_b, link_b = self._pair_ids[k]
            for point in p.getClosestPoints(uid_a, uid_b, horizon, link_a, link_b, physicsClientId=client):
                yield float(point[8])

    def _collides_here(self, static_bounds: FloatArray) -> bool:
        return any(d < self.margin for d in self._distances(max(self.margin, 0.0), static_bounds))

    def _clearance_here(self, static_bounds: FloatArray) -> float:
        """Smallest distance up to the horizon: pairs in order of their bounds' gap until the
        gap alone rules a pair out. (Each pair is asked up to the full horizon: a smaller
        threshold changes PyBullet's depth estimates of deep penetrations.)"""
        horizon, client = CLEARANCE_HORIZON, self._client
        best = horizon
        for k, gap in self._candidates(horizon, static_bounds):
            if gap > best + BOUNDS_SLACK:
                break
            uid_a, link_a, uid_b, link_b = self._pair_ids[k]
            for point in p.getClosestPoints(uid_a, uid_b, horizon, link_a, link_b, physicsClientId=client):
                best = min(best, float(point[8]))
        return best

    # -- batches -----------------------------------------------------------------------------------
    def _check_rows(
        self, batch: FloatArray, along: Along | None = None, stop_at_invalid: bool = False
    ) -> BoolArray:
        """Per row, within limits and collision-free; with ``stop_at_invalid`` the rows after
        the first invalid one are left unchecked (and may read True)."""
        valid = np.asarray(((batch >= self._limits[0]) & (batch <= self._limits[1])).all(axis=1))
        if not valid.any() or (stop_at_invalid and not valid.all()):
            return valid
        with self._in_snapshot(only_arm_moves=along is None):
            for i in np.flatnonzero(valid).tolist():
                valid[i] = not self._collides_here(self._place(batch[i], along, i))
                if stop_at_invalid and not valid[i]:
                    break
        return valid

    def _clearances(self, batch: FloatArray, along: Along | None = None) -> FloatArray:
        with self._in_snapshot(only_arm_moves=along is None):
            return np.array([self._clearance_here(self._place(q, along, i)) for i, q in enumerate(batch)])

    # -- public batch interface ------------------------------------------------------------------
    def is_valid(self, qs: FloatArray) -> BoolArray:
        """For each row of ``qs`` (n, dof): within limits and collision-free."""
        return self._check_rows(np.atleast_2d(np.asarray(qs, dtype=float)))

    def is_valid_along(
        self, qs: FloatArray, body: Body, joint_names: Sequence[str], joint_values: FloatArray
    ) -> BoolArray:
        """Like ``is_valid`` while ``body``'s joints take ``joint_values[i]`` at ``qs[i]``
        (e.g. a drawer pulled by the hand); bodies attached to them follow."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        values = np.asarray(joint_values, dtype=float).reshape(len(batch), -1)
        return self._check_rows(batch, (body, joint_names, values))

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
        fractions = np.array(_coarse_to_fine(steps), dtype=float) / steps
        interior = start + fractions[:, None] * (end - start)
        return bool(np.all(self._check_rows(interior, stop_at_invalid=True)))

    def min_clearance(self, qs: FloatArray) -> FloatArray:
        """Smallest signed distance (m, negative when penetrating) per configuration,
        capped at ``CLEARANCE_HORIZON``; allowed contacts are left out."""
        return self._clearances(np.atleast_2d(np.asarray(qs, dtype=float)))

    def min_clearance_along(
        self, qs: FloatArray, body: Body, joint_names: Sequence[str], joint_values: FloatArray
    ) -> FloatArray:
        """Like ``min_clearance`` while ``body``'s joints take ``joint_values[i]`` at ``qs[i]``."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        values = np.asarray(joint_values, dtype=float).reshape(len(batch), -1)
        return self._clearances(batch, (body, joint_names, values))

    def colliding_pairs(self, q: FloatArray) -> list[tuple[str, str]]:
        """Names of the pairs closer than the margin at ``q`` (for error messages)."""
        horizon, names = max(self.margin, 0.0), []
        with self._in_snapshot(only_arm_moves=True):
            static_bounds = self._place(np.asarray(q, dtype=float))
            for k, _ in self._candidates(horizon, static_bounds):
                uid_a, link_a, uid_b, link_b = self._pair_ids[k]
                points = p.getClosestPoints(
                    uid_a, uid_b, horizon, link_a, link_b, physicsClientId=self._client
                )
                if any(point[8] < self.margin for point in points):
                    body_a, _, body_b, _ = self._pairs[k]
                    first = body_a.link_name(link_a) if body_a is self.robot.body else body_a.name
                    second = body_b.link_name(link_b)
                    names.append((first, second) if body_a is body_b else (first, f"{body_b.name}/{second}"))
        return sorted(set(names))


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
