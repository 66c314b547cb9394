"""The lowest clearance along a run of arm configurations, measured exactly only where it can matter.

The kinematic judge wants, per run of states, the smallest clearance, the first state where it
is reached and the first state that collides; measuring every pair at every state (PyBullet's
``getClosestPoints``, about 0.2 ms a state in the kitchen) is most of its time. But a pair's
distance cannot change faster than its links move: turning arm joint ``k`` by ``dq`` moves every
point of a link it carries by at most ``|dq|`` times the point's distance from the joint's axis,
and that distance is at most the link's reach from the joint (`reach_weights`: the lengths of the
fixed offsets between the link frames down the chain, plus the link's extent around its own frame;
a carried body counts as the link holding it). So a pair measured at ``v`` at state ``a`` is at
least ``v - W_p . |q - q_a|`` at state ``q``, where ``W_p`` sums, per joint, the reach of whichever
of the pair's two sides that joint moves alone (a joint that moves both moves them together).

`lowest_clearance` measures every ``PREPASS_STRIDE``-th state and the last fully, which gives a
threshold ``T`` (the lowest clearance met so far, or the ``ceiling`` the caller already has, never
below 0), then walks the states between in order and, at each, measures only the pairs whose bound
from the states measured on either side does not prove them above ``T`` (or, for a pair that
counts only when negative, an intended contact deeper than allowed or a kept clearance broken,
above 0). What it does not measure is proved
above ``T``: a state can be neither the lowest (nor tie with it) nor a collision through it. So the
lowest value, the first state reaching it and the first colliding state are exactly those of
measuring every pair at every state, whenever the lowest is below the ceiling
(tests/world/test_clearance_scan.py holds the two together, and every bound to the distances
PyBullet measures). With ``until_collision`` (a ceiling of 0) it looks only for the first collision,
in order, and stops there: the planner's replay of a sample.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Final

import numpy as np
import numpy.typing as npt
import pybullet as p

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import BASE_LINK, Body
from kitchen_tamp.world.collision.checked_pairs import CheckedPairs
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.transforms import FloatArray

IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]

PREPASS_STRIDE: Final = 16
"""Every this many states (and the last) are measured first, for the threshold and as anchors."""

BOUND_SLACK: Final = 1e-4
"""A state is measured unless every pair's bound clears the threshold by more than this (m): room
for PyBullet's distance tolerance, far above it."""


@dataclass(frozen=True)
class LowestClearance:
    """What the judge needs of a run's clearances: the lowest (its first state) and the first
    state closer than allowed (negative clearance), or None; and how many states were measured."""

    index: int
    value: float
    first_collision: int | None
    measured: int

    @staticmethod
    def of(clearances: FloatArray) -> LowestClearance:
        """The summary of clearances measured at every state."""
        bad = np.flatnonzero(clearances < 0.0)
        lowest = int(np.argmin(clearances))
        return LowestClearance(lowest, float(clearances[lowest]), int(bad[0]) if len(bad) else None,
                               len(clearances))


def _extent(body: Body, link: int, around: Sequence[float]) -> float:
    """The farthest corner of the link's axis-aligned bounds from ``around``: the link's shapes lie
    no farther from it."""
    low, high = p.getAABB(body.uid, link, physicsClientId=body.client)
    return max(math.dist(corner, around) for corner in itertools.product(*zip(low, high, strict=True)))


def reach_weights(
    checked: CheckedPairs, robot: Robot, arm: Sequence[int], carried: Sequence[Attachment]
) -> FloatArray | None:
    """Per checked pair and arm joint, how far one radian of that joint alone can change the pair's
    distance (m/rad), from the scene as it is now (the fingers and what the hand carries fixed);
    None when an arm joint is not revolute (then no bound is used)."""
    body = robot.body
    if not all(joint.revolute for joint in body.joints if joint.index in arm):
        return None
    parent = {j.index: j.parent_index for j in body.joints}
    links = sorted(parent)
    states = p.getLinkStates(body.uid, links, computeForwardKinematics=True, physicsClientId=body.client)
    origin = {link: state[4] for link, state in zip(links, states, strict=True)}
    column = {joint: c for c, joint in enumerate(arm)}

    def chain_reach(link: int) -> FloatArray:
        """Per arm joint: the joint's distance bound to ``link``'s frame origin (the fixed offsets
        from the link up to the joint's child link summed), or NaN when it does not move the link."""
        reach, length = np.full(len(arm), np.nan), 0.0
        while link != BASE_LINK:
            if link in column:
                reach[column[link]] = length
            up = parent[link]
            if up == BASE_LINK:
                break
            length += math.dist(origin[link], origin[up])
            link = up
        return reach

    held_by = {a.child.uid: body.link_index(a.parent_link) for a in carried}
    sides: dict[tuple[int, int], int] = {}
    reaches: list[FloatArray] = []
    for side, link in itertools.chain.from_iterable(((a, i), (b, j)) for a, i, b, j in checked.pairs):
        if (side.uid, link) in sides:
            continue
        holder = link if side is body else held_by.get(side.uid, BASE_LINK)
        reach = chain_reach(holder) if holder != BASE_LINK else np.full(len(arm), np.nan)
        if not np.all(np.isnan(reach)):
            reach += _extent(side, link, origin[holder])
        sides[side.uid, link] = len(reaches)
        reaches.append(reach)
    table = np.array(reaches)
    moved, reach_table = ~np.isnan(table), np.nan_to_num(table)
    side_a = np.array([sides[a.uid, i] for a, i, _, _ in checked.pairs], dtype=np.intp)
    side_b = np.array([sides[b.uid, j] for _, _, b, j in checked.pairs], dtype=np.intp)
    # A joint moving both sides moves them together; one moving a single side moves it by its reach.
    return np.where(moved[side_a] != moved[side_b], reach_table[side_a] + reach_table[side_b], 0.0)


def sliding_weights(
    checked: CheckedPairs, body: Body, joint_names: Sequence[str], attachments: Sequence[Attachment]
) -> FloatArray | None:
    """Per checked pair and joint of ``body`` (a drawer's slide), how far one metre of that joint
    alone changes the pair's distance: 1 when it moves one side of the pair (a link beyond it, or a
    body riding on one) and not the other, else 0; None unless every joint is prismatic (a
    prismatic joint moves everything beyond it by exactly its travel)."""
    joints = [body.joint(name) for name in joint_names]
    if not all(joint.movable and not joint.revolute for joint in joints):
        return None
    parent = {j.index: j.parent_index for j in body.joints}

    def beyond(link: int, joint: int) -> bool:
        while link != BASE_LINK:
            if link == joint:
                return True
            link = parent[link]
        return False

    riding = {a.child.uid: a for a in attachments}

    def moves(side: Body, link: int, joint: int) -> bool:
        if side is body:
            return beyond(link, joint)
        ride = riding.get(side.uid)
        return ride is not None and moves(ride.parent, ride.parent.link_index(ride.parent_link), joint)

    return np.array([[float(moves(a, i, joint.index) != moves(b, j, joint.index)) for joint in joints]
                     for a, i, b, j in checked.pairs]).reshape(len(checked.pairs), len(joints))


def pair_values(checked: CheckedPairs, pairs: IntArray, horizon: float, client: int) -> FloatArray:
    """The given pairs' distances plus allowances at the current state (the horizon plus allowance
    for a pair farther than it)."""
    values = []
    for k in pairs.tolist():
        uid_a, link_a, uid_b, link_b = checked.pair_ids[k]
        points = p.getClosestPoints(uid_a, uid_b, horizon, link_a, link_b, physicsClientId=client)
        values.append(min((float(point[8]) for point in points), default=horizon) + checked.allowances[k])
    return np.array(values)


Measure = Callable[[int], tuple[float, FloatArray]]
"""The exact clearance of state ``i`` and a lower bound on every pair's value (distance plus
allowance) there."""
MeasurePairs = Callable[[int, IntArray], FloatArray]
"""The values of the given pairs at state ``i`` (the horizon plus allowance beyond it)."""


def lowest_clearance(
    qs: FloatArray,
    measure: Measure,
    measure_pairs: MeasurePairs,
    weights: FloatArray,
    only_negative: BoolArray,
    ceiling: float,
    until_collision: bool = False,
) -> LowestClearance:
    """`LowestClearance` of the states ``qs``: every state ``PREPASS_STRIDE`` apart (and the last)
    by ``measure``, then at the states between only the pairs whose bounds (pairs x joints
    ``weights``; ``only_negative`` marks the pairs counted only when negative) do not prove them above
    the threshold, by ``measure_pairs`` (see the module's docstring). Exact whenever the lowest
    clearance is below ``ceiling`` (pass the lowest the caller has met, or infinity).

    With ``until_collision`` only the first collision is looked for (pass a ``ceiling`` of 0): the
    states are measured in order and the scan stops at the first collision, so the lowest is
    only that of the states measured."""
    count = len(qs)
    values = np.full(count, np.inf)
    full: dict[int, FloatArray] = {}
    anchors = sorted(set(range(0, count, PREPASS_STRIDE)) | {count - 1})
    for i in anchors[:1] if until_collision else anchors:
        values[i], full[i] = measure(i)
    threshold = max(0.0, min(ceiling, float(values.min())))
    measured = len(full)
    for before, after in itertools.pairwise(anchors):
        if until_collision:
            if values[before] < 0.0:
                break  # the first collision: every state before it was proved or measured free
            values[after], full[after] = measure(after)
            measured += 1
        # Lower bounds on every pair's value at the states between: from the state after, and from
        # the last state measured before (each pair's bound there carried to it).
        from_after = full[after] - np.abs(qs[before + 1 : after] - qs[after]) @ weights.T
        known, known_at, start = full[before], before, before + 1
        while start < after:
            low = np.maximum(known - np.abs(qs[start:after] - qs[known_at]) @ weights.T,
                             from_after[start - before - 1 :])
            below = low <= np.where(only_negative, 0.0, threshold) + BOUND_SLACK
            rows = np.flatnonzero(below.any(axis=1))
            if len(rows) == 0:
                break  # every pair proved above the threshold at every state left
            row = int(rows[0])
            i, near = start + row, np.flatnonzero(below[row])
            found = measure_pairs(i, near)
            known = low[row].copy()
            known[near] = found
            known_at, start = i, i + 1
            counted = found[~only_negative[near] | (found < 0.0)]
            values[i] = float(counted.min()) if len(counted) else np.inf
            threshold = max(0.0, min(threshold, values[i]))
            measured += 1
            if until_collision and values[i] < 0.0:
                break
        if until_collision and bool(np.any(values[before + 1 : after] < 0.0)):
            break
    bad = np.flatnonzero(values < 0.0)
    lowest = int(np.argmin(values))
    return LowestClearance(lowest, float(values[lowest]), int(bad[0]) if len(bad) else None, measured)
