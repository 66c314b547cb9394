"""Which link pairs a collision check measures, how deep each may touch, and in which order:
the pair policy and its axis-aligned-bounds broadphase.

Checked: every moving robot link against every other body's links; every link
of a body the robot carries against every other body and every robot link;
robot links against each other when at least two movable joints separate them
(links joined by one joint touch by construction); and, while a joint of an
obstacle moves (a drawer pulled by the hand), the bodies riding on it against
the links of its body that move relative to them and against every other body.

An intended contact (``AllowedContact``: the fingers on the box being grasped,
the gripper on the handle being pulled, a box on its support) does not remove
a pair: it lets the pair touch down to ``max_penetration``; deeper is a
collision. Clearance margins do not apply to such a pair, and clearances leave
it out while it is within its bound (counting it as ``distance +
max_penetration`` when deeper). A kept clearance (``KeptClearance``) is the other way
round: the robot and what it carries must stay that far from a body (a box beside the
one the hand works on), whatever the query margin; its pairs carry the clearance as a
negative allowance. ``CheckedPairs.policy()`` gives the same table as plain data
(``CheckedLinkPair`` by body and link names), which is what other collision
models (Drake's, in ``motion``) check, so the pairs are decided here only.

The pairs are listed once, link by link. Per configuration the moving links'
axis-aligned bounds are read (``getAABB`` is exact and current after a joint
reset) and only the pairs whose bounds come within the query distance are
handed back (bounds ``g`` apart mean shapes at least ``g`` apart), the most
overlapping first, so a checker measuring them in that order meets a collision
early.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Final

import numpy as np
import pybullet as p

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import BASE_LINK, Body
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.transforms import FloatArray

BOUNDS_SLACK = 1e-6
"""Pairs whose bounds are within the query distance plus this (m) are measured exactly."""

CONTACT_PENETRATION_BOUND: Final = 0.002
"""How deep (m) an intended contact may press in before it counts as a collision."""

LinkPair = tuple[Body, int, Body, int]
"""(body, link index, other body, other link index)."""

BoundsRow = tuple[int, int]
"""(body uid, link index) whose axis-aligned bounds are one row of the bounds table."""

_flatten = itertools.chain.from_iterable


@dataclass(frozen=True)
class AllowedContact:
    """An intended contact: robot links (all when None) -- or, when ``carried`` is given, that
    carried body -- may touch ``body``'s link (all links when None), at most
    ``max_penetration`` deep.

    Used for the contacts an action means: the fingers around the box being
    grasped, the gripper on the drawer handle, a box on its support.
    """

    body: str
    link: str | None = None
    robot_links: frozenset[str] | None = None
    carried: str | None = None
    max_penetration: float = CONTACT_PENETRATION_BOUND

    def allows(self, robot_link: str, body: str, link: str) -> bool:
        """Whether this contact covers ``robot_link`` touching ``body``'s ``link``."""
        return (
            self.carried is None
            and body == self.body
            and (self.link is None or self.link == link)
            and (self.robot_links is None or robot_link in self.robot_links)
        )

    def allows_carried(self, carried: str, body: str, link: str) -> bool:
        """Whether this contact covers the carried body ``carried`` touching ``body``'s ``link``."""
        return carried == self.carried and body == self.body and (self.link is None or self.link == link)


@dataclass(frozen=True)
class KeptClearance:
    """The robot and what it carries keep at least ``clearance`` (m) from ``body`` (unless an
    intended contact covers the pair).

    Used by the skills' straight moves near the boxes beside the one they work on: a
    plan that passes a neighbour within a fraction of a millimetre is touched under
    physics, where the hand lags the plan and contacts start before shapes meet.
    """

    body: str
    clearance: float


@dataclass(frozen=True)
class CheckedLinkPair:
    """One checked pair by names: a collision when closer than the query margin less ``allowance``."""

    body_a: str
    link_a: str
    body_b: str
    link_b: str
    allowance: float = 0.0
    """Penetration (m) tolerated: an intended contact's bound; negative, a kept clearance
    (the pair collides closer than that); 0 for every other pair."""


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


def _riding_pairs(
    riding: Sequence[Attachment], obstacle_links: Sequence[tuple[Body, int]]
) -> list[tuple[Body, int, Body, int, float]]:
    """Bodies riding an obstacle's link against the links of that obstacle that move relative to
    it (a movable joint between) and against every other obstacle not riding the same link."""
    pairs: list[tuple[Body, int, Body, int, float]] = []
    for ride in riding:
        parent, child, link = ride.parent, ride.child, ride.parent.link_index(ride.parent_link)
        fellow = {r.child.name for r in riding if r.parent is parent and r.parent_link == ride.parent_link}
        for c in _collision_links(child):
            for other, other_link in obstacle_links:
                if other is parent:
                    if _movable_joints_between(parent, link, other_link) == 0:
                        continue
                elif other.name in fellow:
                    continue
                pairs.append((child, c, other, other_link, 0.0))
    return pairs


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


class CheckedPairs:
    """The link pairs checked for a robot among obstacles while it carries some bodies (and,
    given ``riding``, while those bodies ride a moving obstacle joint), how deep each may
    touch, and which of them to measure at the current state, most overlapping bounds first."""

    def __init__(
        self,
        robot: Robot,
        obstacles: Sequence[Body],
        carried: Sequence[Attachment],
        allowed: Iterable[AllowedContact] = (),
        riding: Sequence[Attachment] = (),
        kept: Iterable[KeptClearance] = (),
    ) -> None:
        self.robot = robot
        self.allowed: tuple[AllowedContact, ...] = tuple(allowed)
        self.kept: tuple[KeptClearance, ...] = tuple(kept)
        self._client = robot.body.client
        body = robot.body
        moving, self_pairs = _robot_link_sets(body, robot.description.arm_joints[0])
        robot_links = _collision_links(body)
        obstacle_links = [(o, b) for o in obstacles for b in _collision_links(o)]
        moving_rows = [(body, i) for i in robot_links if i in moving]
        moving_rows += [(a.child, i) for a in carried for i in _collision_links(a.child)]
        static_rows = [(body, i) for i in robot_links if i not in moving] + obstacle_links
        pairs: list[tuple[Body, int, Body, int, float]] = [
            (body, a, o, b, self._robot_allowance(a, o, b))
            for a in robot_links
            if a in moving
            for o, b in obstacle_links
        ]
        for child in (a.child for a in carried):
            for c in _collision_links(child):
                pairs += [(child, c, o, b, self._carried_allowance(child, o, b)) for o, b in obstacle_links]
                pairs += [(child, c, body, b, self._robot_allowance(b, child, c)) for b in robot_links]
        pairs += [(body, a, body, b, 0.0) for a, b in self_pairs]
        pairs += _riding_pairs(riding, obstacle_links)
        self.moving_rows: tuple[BoundsRow, ...] = tuple((b.uid, i) for b, i in moving_rows)
        self.static_rows: tuple[BoundsRow, ...] = tuple((b.uid, i) for b, i in static_rows)
        self.pairs: tuple[LinkPair, ...] = tuple((a, i, b, j) for a, i, b, j, _ in pairs)
        self.pair_ids: list[tuple[int, int, int, int]] = [(a.uid, i, b.uid, j) for a, i, b, j, _ in pairs]
        self.allowances: FloatArray = np.array([allowance for *_, allowance in pairs], dtype=float)
        """Per pair, the penetration (m) it may reach before it counts as a collision (negative:
        the clearance it must keep)."""
        self.kept_horizon = max(0.0, -float(self.allowances.min(initial=0.0)))
        """The largest kept clearance (m): a check must measure pairs at least this far apart."""
        # Bounds are a flat table of (low xyz, high xyz) rows. Per pair and axis,
        # low_a - high_b and low_b - high_a: the largest of the six is the gap.
        row_of = {(b.name, i): r for r, (b, i) in enumerate(moving_rows + static_rows)}
        rows_a = 6 * np.array([row_of[a.name, i] for a, i, _, _ in self.pairs], dtype=np.intp)[:, None]
        rows_b = 6 * np.array([row_of[b.name, j] for _, _, b, j in self.pairs], dtype=np.intp)[:, None]
        axes = np.arange(3)
        self._gap_minuends = np.hstack([rows_a + axes, rows_b + axes]).T.reshape(-1)
        self._gap_subtrahends = np.hstack([rows_b + 3 + axes, rows_a + 3 + axes]).T.reshape(-1)

    def _robot_allowance(self, robot_link: int, other: Body, other_link: int) -> float:
        robot_name, other_name = self.robot.body.link_name(robot_link), other.link_name(other_link)
        bounds = [a.max_penetration for a in self.allowed if a.allows(robot_name, other.name, other_name)]
        return max(bounds) if bounds else self._kept_allowance(other)

    def _carried_allowance(self, carried: Body, other: Body, other_link: int) -> float:
        other_name = other.link_name(other_link)
        bounds = [
            a.max_penetration for a in self.allowed if a.allows_carried(carried.name, other.name, other_name)
        ]
        return max(bounds) if bounds else self._kept_allowance(other)

    def _kept_allowance(self, other: Body) -> float:
        """Minus the largest clearance kept from ``other`` (0 when none is)."""
        return -max((k.clearance for k in self.kept if k.body == other.name), default=0.0)

    def policy(self) -> tuple[CheckedLinkPair, ...]:
        """The pair table as plain data (names), for other collision models."""
        return tuple(
            CheckedLinkPair(a.name, a.link_name(i), b.name, b.link_name(j), float(allowance))
            for (a, i, b, j), allowance in zip(self.pairs, self.allowances, strict=True)
        )

    def bounds(self, rows: Sequence[BoundsRow]) -> FloatArray:
        """Current axis-aligned bounds of the rows' links, flat: (low xyz, high xyz) per row."""
        boxes = [p.getAABB(uid, link, physicsClientId=self._client) for uid, link in rows]
        return np.fromiter(_flatten(_flatten(boxes)), dtype=float, count=6 * len(rows))

    def static_bounds(self) -> FloatArray:
        """Current bounds of the links the arm does not move (read again only when they move)."""
        return self.bounds(self.static_rows)

    def candidates(self, horizon: float, static_bounds: FloatArray) -> Iterator[tuple[int, float]]:
        """(pair, gap between its bounds) for the pairs whose bounds come within ``horizon``,
        the most overlapping first (made as they are asked for: a caller measuring the nearest
        pairs stops after a few)."""
        table = np.concatenate([self.bounds(self.moving_rows), static_bounds])
        gaps = (table.take(self._gap_minuends) - table.take(self._gap_subtrahends)).reshape(6, -1).max(axis=0)
        near = np.flatnonzero(gaps <= horizon + BOUNDS_SLACK)
        near = near[np.argsort(gaps[near], kind="stable")]
        return zip(near.tolist(), gaps[near].tolist(), strict=True)



_MADE_TABLES: dict[tuple[object, ...], CheckedPairs] = {}
"""Tables made by `checked_pairs_of`, by what they were made of (at most `_MAX_MADE_TABLES`)."""
_MAX_MADE_TABLES: Final = 64


def checked_pairs_of(
    robot: Robot,
    obstacles: Sequence[Body],
    carried: Sequence[Attachment],
    allowed: Sequence[AllowedContact] = (),
    riding: Sequence[Attachment] = (),
    kept: Sequence[KeptClearance] = (),
) -> CheckedPairs:
    """``CheckedPairs(robot, obstacles, carried, allowed, riding, kept)``, made once for the same
    bodies, contacts, rides and clearances: a table reads of an attachment only which bodies
    and link it joins, and nothing of it changes once made, while the skills and the judges
    make a checker per sample and per run of states, mostly of the same scene."""
    key = (robot, tuple(obstacles), tuple(a.child for a in carried), tuple(allowed),
           tuple((r.parent, r.parent_link, r.child) for r in riding), tuple(kept))
    table = _MADE_TABLES.get(key)
    if table is None:
        if len(_MADE_TABLES) >= _MAX_MADE_TABLES:
            _MADE_TABLES.pop(next(iter(_MADE_TABLES)))
        table = _MADE_TABLES[key] = CheckedPairs(robot, obstacles, carried, allowed, riding, kept)
    return table
