"""Collision checking of arm configurations against a frozen snapshot of the scene.

A ``PyBulletCollisionChecker`` is the only thing a motion planner needs from the world:
``is_valid`` over a batch of configurations, ``segment_valid`` between two of
them, the joint limits, and ``min_clearance`` for verification (``lowest_clearance``: a run's
closest approach and first collision, measured only where they can be, ``clearance_scan``). It captures the
scene when it is made (what the arm carries, where the drawer is), so it stays
right even if the scene changes later, and it always leaves the scene as it
found it.

Which link pairs are checked, and which of them are measured at a
configuration (an axis-aligned-bounds broadphase, most overlapping first), is
``checked_pairs``; an intended contact is a pair that may touch down to its
bound, so every distance here is a pair's distance plus its allowance (negative
means deeper than allowed). While a drawer moves (``is_valid_along``), the boxes
riding in it are checked against the cabinet too. Here, per configuration, the arm is reset, the pairs the
broadphase hands over go to ``getClosestPoints``, stopping at the first
collision, and the scene is saved and restored as raw PyBullet values rather
than ``Pose`` objects: tens of microseconds per configuration.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager

import numpy as np
import pybullet as p
from numpy.typing import NDArray

from kitchen_tamp.joint_spacing import interior_fractions
from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.collision.carried_placement import CarriedPlacement
from kitchen_tamp.world.collision.checked_pairs import (
    BOUNDS_SLACK,
    CheckedLinkPair,
    CheckedPairs,
    checked_pairs_of,
)
from kitchen_tamp.world.collision.checked_pairs import AllowedContact as AllowedContact
from kitchen_tamp.world.collision.checked_pairs import KeptClearance as KeptClearance
from kitchen_tamp.world.collision.clearance_scan import (
    LowestClearance,
    lowest_clearance,
    pair_values,
    reach_weights,
    sliding_weights,
)
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray

BoolArray = NDArray[np.bool_]

CLEARANCE_HORIZON = 0.5
"""Distance (m) beyond which ``min_clearance`` stops looking and reports this value."""

STATE_TOLERANCE = 1e-12
"""Scene states this close count as the snapshot (PyBullet echoes orientations to an ulp)."""

RawBodyState = tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]
"""A body's centre-of-mass position and quaternion and its movable joints' positions."""

_flatten = itertools.chain.from_iterable


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


Along = tuple[Body, Sequence[str], FloatArray]
"""A body whose named joints take the i-th row of the values at the i-th configuration."""


class PyBulletCollisionChecker:
    """Batch collision checks of arm configurations in a snapshot of a scene."""

    def __init__(
        self,
        scene: Scene,
        robot: Robot,
        allowed: Iterable[AllowedContact] = (),
        margin: float = 0.0,
        kept: Iterable[KeptClearance] = (),
    ) -> None:
        self.scene = scene
        self.robot = robot
        self.margin = float(margin)
        self.allowed: tuple[AllowedContact, ...] = tuple(allowed)
        self.kept: tuple[KeptClearance, ...] = tuple(kept)
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
        self._placements = tuple(CarriedPlacement(a) for a in self.carried)
        self._arm = robot.body.joint_indices(robot.description.arm_joints)
        self._robot_slot = self._bodies.index(robot.body)
        self._arm_in_robot_state = [self._joints[self._robot_slot].index(i) for i in self._arm]
        self._carried_slots = tuple(self._bodies.index(a.child) for a in self.carried)
        self._checked = checked_pairs_of(robot, self.obstacles, self.carried, self.allowed, (), self.kept)
        self._pairs = self._checked.pairs
        self._static_bounds = self._checked.static_bounds()
        riding = tuple(
            a for a in scene.attachments if a.parent is not robot.body and a.child in self.obstacles
        )
        self._checked_along = self._checked
        if riding:
            self._checked_along = checked_pairs_of(
                robot, self.obstacles, self.carried, self.allowed, riding, self.kept
            )

    def policy(self) -> tuple[CheckedLinkPair, ...]:
        """The pairs this checker checks with the arm alone moving, as plain data."""
        return self._checked.policy()

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
        return static_bounds if along is None else self._checked.static_bounds()

    def _distances(
        self, checked: CheckedPairs, horizon: float, static_bounds: FloatArray
    ) -> Iterator[tuple[int, float]]:
        """(pair, how far it is from colliding) for the checked pairs within ``horizon`` at the
        current state: a pair's distance less the margin (or less its kept clearance when that
        is larger), or for an intended contact its distance plus its allowance (the margin
        does not apply to what is meant to touch)."""
        client, ids, allowances = self._client, checked.pair_ids, checked.allowances
        for k, _ in checked.candidates(horizon, static_bounds):
            uid_a, link_a, uid_b, link_b = ids[k]
            allowance = float(allowances[k])
            if allowance > 0.0:  # an intended contact: touching is allowed down to its bound
                offset = allowance
            elif allowance < 0.0:  # a kept clearance, or the margin when that is larger
                offset = min(allowance, -self.margin)
            else:
                offset = -self.margin
            for point in p.getClosestPoints(uid_a, uid_b, horizon, link_a, link_b, physicsClientId=client):
                yield k, float(point[8]) + offset

    def _collides_here(self, checked: CheckedPairs, static_bounds: FloatArray) -> bool:
        horizon = max(self.margin, checked.kept_horizon)
        return any(d < 0.0 for _, d in self._distances(checked, horizon, static_bounds))

    def _clearance_here(
        self, checked: CheckedPairs, static_bounds: FloatArray, pair_bounds: FloatArray | None = None
    ) -> float:
        """Smallest distance up to the horizon: pairs in order of their bounds' gap until the
        gap alone rules a pair out. (Each pair is asked up to the full horizon: a smaller
        threshold changes PyBullet's depth estimates of deep penetrations.) Given
        ``pair_bounds``, fills it with a lower bound on every pair's distance plus allowance:
        measured, or its bounds' gap, or the horizon."""
        horizon, client = CLEARANCE_HORIZON, self._client
        best = horizon
        if pair_bounds is not None:
            pair_bounds[:] = horizon + checked.allowances
        candidates = checked.candidates(horizon, static_bounds)
        for k, gap in candidates:
            # A pair's value is at least its gap less the largest kept clearance (0 without one).
            if gap - checked.kept_horizon > best + BOUNDS_SLACK:
                if pair_bounds is not None:
                    pair_bounds[k] = gap + checked.allowances[k]
                    for rest, rest_gap in candidates:
                        pair_bounds[rest] = rest_gap + checked.allowances[rest]
                break
            uid_a, link_a, uid_b, link_b = checked.pair_ids[k]
            allowance = float(checked.allowances[k])
            for point in p.getClosestPoints(uid_a, uid_b, horizon, link_a, link_b, physicsClientId=client):
                distance = float(point[8]) + allowance
                if pair_bounds is not None:
                    pair_bounds[k] = min(pair_bounds[k], distance)
                if allowance == 0.0 or distance < 0.0:  # an intended contact counts only when too deep
                    best = min(best, distance)
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
        checked = self._checked if along is None else self._checked_along
        with self._in_snapshot(only_arm_moves=along is None):
            for i in np.flatnonzero(valid).tolist():
                valid[i] = not self._collides_here(checked, self._place(batch[i], along, i))
                if stop_at_invalid and not valid[i]:
                    break
        return valid

    def _clearances(self, batch: FloatArray, along: Along | None = None) -> FloatArray:
        checked = self._checked if along is None else self._checked_along
        with self._in_snapshot(only_arm_moves=along is None):
            return np.array(
                [self._clearance_here(checked, self._place(q, along, i)) for i, q in enumerate(batch)]
            )

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
        """Whether the straight joint-space segment is valid at the states
        ``kitchen_tamp.joint_spacing`` puts ``resolution_rad`` apart.

        The endpoints are checked first, then the interior coarse-to-fine, so a
        blocked segment usually fails after a few checks.
        """
        start, end = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
        if not bool(np.all(self.is_valid(np.stack([start, end])))):
            return False
        fractions = interior_fractions(start, end, resolution_rad)
        if len(fractions) == 0:
            return True
        interior = start + fractions[:, None] * (end - start)
        return bool(np.all(self._check_rows(interior, stop_at_invalid=True)))

    def min_clearance(self, qs: FloatArray) -> FloatArray:
        """Smallest signed distance (m, negative when penetrating) per configuration,
        capped at ``CLEARANCE_HORIZON``; an intended contact counts only when deeper than
        allowed, from its allowed depth."""
        return self._clearances(np.atleast_2d(np.asarray(qs, dtype=float)))

    def lowest_clearance(
        self, qs: FloatArray, ceiling: float = float("inf"), until_collision: bool = False,
        along: Along | None = None,
    ) -> LowestClearance:
        """The lowest of ``min_clearance(qs)`` (``min_clearance_along`` with ``along``), its first row
        and the first negative row, measuring only the rows where they can be (`clearance_scan`);
        exact whenever the lowest is below ``ceiling``; with ``until_collision`` (and a ``ceiling``
        of 0), only the first negative row."""
        batch, client = np.atleast_2d(np.asarray(qs, dtype=float)), self._client
        checked = self._checked if along is None else self._checked_along
        if along is not None:  # a row of joint values per configuration
            along = (along[0], along[1], np.asarray(along[2], dtype=float).reshape(len(batch), -1))
        if len(batch) <= 2:
            return LowestClearance.of(self._clearances(batch, along))
        with self._in_snapshot(only_arm_moves=along is None):

            def measure(i: int) -> tuple[float, FloatArray]:
                bounds = np.empty(len(checked.pairs))
                return self._clearance_here(checked, self._place(batch[i], along, i), bounds), bounds

            def measure_pairs(i: int, pairs: NDArray[np.intp]) -> FloatArray:
                self._place(batch[i], along, i)
                return pair_values(checked, pairs, CLEARANCE_HORIZON, client)

            weights, rows = self._reach_weights, batch
            if along is not None:  # the arm's joints, then the slide's
                arm = reach_weights(checked, self.robot, self._arm, self.carried)
                slide = sliding_weights(checked, along[0], along[1], self._attachments)
                weights = None if arm is None or slide is None else np.hstack([arm, slide])
                rows = np.hstack([batch, along[2]])
            if weights is None:
                return LowestClearance.of(np.array([measure(i)[0] for i in range(len(batch))]))
            # An intended contact or a kept clearance counts only when negative (`_clearance_here`).
            only_negative, until = checked.allowances != 0.0, until_collision
            return lowest_clearance(rows, measure, measure_pairs, weights, only_negative, ceiling, until)

    @functools.cached_property
    def _reach_weights(self) -> FloatArray | None:
        """`reach_weights` of the pairs checked with the arm alone moving (first read in the snapshot)."""
        return reach_weights(self._checked, self.robot, self._arm, self.carried)

    def min_clearance_along(
        self, qs: FloatArray, body: Body, joint_names: Sequence[str], joint_values: FloatArray
    ) -> FloatArray:
        """Like ``min_clearance`` while ``body``'s joints take ``joint_values[i]`` at ``qs[i]``."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        values = np.asarray(joint_values, dtype=float).reshape(len(batch), -1)
        return self._clearances(batch, (body, joint_names, values))

    def colliding_pairs(
        self, q: FloatArray, along: tuple[Body, Sequence[str], FloatArray] | None = None
    ) -> list[tuple[str, str]]:
        """Names of the pairs closer than the margin (intended contacts: deeper than their
        allowance) at ``q``, with
        ``along``'s joints at the given values (for error messages)."""
        checked = self._checked if along is None else self._checked_along
        horizon, names = max(self.margin, checked.kept_horizon), []
        moved = None
        if along is not None:
            moved = (along[0], along[1], np.atleast_2d(np.asarray(along[2], dtype=float)))
        with self._in_snapshot(only_arm_moves=along is None):
            static_bounds = self._place(np.asarray(q, dtype=float), moved)
            colliding = {k for k, d in self._distances(checked, horizon, static_bounds) if d < 0.0}
            for k in sorted(colliding):
                body_a, link_a, body_b, link_b = checked.pairs[k]
                first = body_a.link_name(link_a) if body_a is self.robot.body else body_a.name
                second = body_b.link_name(link_b)
                names.append((first, second) if body_a is body_b else (first, f"{body_b.name}/{second}"))
        return sorted(set(names))


def make_collision_checker(
    scene: Scene,
    robot: Robot,
    allowed: Iterable[AllowedContact] = (),
    margin: float = 0.0,
    kept: Iterable[KeptClearance] = (),
) -> PyBulletCollisionChecker:
    """The factory motion planners are given: a checker of the scene as it is now."""
    return PyBulletCollisionChecker(scene, robot, allowed, margin, kept)
