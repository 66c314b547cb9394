"""The judge's clearance scan: every pair's distance changes no faster than its reach bound says,
and measuring only where the bounds leave doubt finds what measuring every state finds."""

from __future__ import annotations

import numpy as np
import pybullet as p
import pytest

from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
from kitchen_tamp.world import Body, Robot, Scene, make_collision_checker
from kitchen_tamp.world.collision.checked_pairs import AllowedContact, KeptClearance, checked_pairs_of
from kitchen_tamp.world.collision.checker import CLEARANCE_HORIZON
from kitchen_tamp.world.collision.clearance_scan import LowestClearance, reach_weights
from tests.world.conftest import sugar_riding_in_drawer


def _hold_sugar(scene: Scene, robot: Robot) -> Body:
    """Attach the sugar box just below the fingertips, the fingers half closed."""
    box = scene.body("sugar")
    robot.set_configuration(robot.mid_configuration())
    robot.set_gripper_width(robot.max_gripper_width / 2.0)
    box.reset_base_pose(robot.tool_pose().translated((0.0, 0.0, -0.12)))
    scene.attach(box, robot.body, robot.description.hand_link)
    return box


def _pair_distances(pair_ids: list[tuple[int, int, int, int]], client: int) -> np.ndarray:
    """Each pair's distance at the current state (NaN beyond the horizon)."""
    distances = np.full(len(pair_ids), np.nan)
    for k, (uid_a, link_a, uid_b, link_b) in enumerate(pair_ids):
        points = p.getClosestPoints(uid_a, uid_b, CLEARANCE_HORIZON, link_a, link_b, physicsClientId=client)
        if points:
            distances[k] = min(point[8] for point in points)
    return distances


@pytest.mark.parametrize("holding", [False, True])
def test_a_pair_moves_no_faster_than_its_reach_bound(panda_scene: tuple[Scene, Robot], holding: bool) -> None:
    scene, robot = panda_scene
    if holding:
        _hold_sugar(scene, robot)
    carried = [a for a in scene.attachments if a.parent is robot.body]
    obstacles = [b for b in scene.bodies if b is not robot.body and all(b is not a.child for a in carried)]
    checked = checked_pairs_of(robot, obstacles, carried)
    arm = robot.body.joint_indices(robot.description.arm_joints)
    weights = reach_weights(checked, robot, arm, carried)
    assert weights is not None and weights.shape == (len(checked.pairs), robot.dof)
    rng = np.random.default_rng(7)
    client, largest_share, compared = robot.body.client, 0.0, 0
    for _ in range(60):
        q1 = rng.uniform(robot.lower, robot.upper)
        q2 = np.clip(q1 + rng.uniform(-0.3, 0.3, robot.dof), robot.lower, robot.upper)
        measured = []
        for q in (q1, q2):
            robot.set_configuration(q)
            scene.update_attachments()
            measured.append(_pair_distances(checked.pair_ids, client))
        both = ~np.isnan(measured[0]) & ~np.isnan(measured[1])
        change = np.abs(measured[1] - measured[0])[both]
        bound = (weights @ np.abs(q2 - q1))[both]
        # Within 10 um, a tenth of the scan's slack: a carried box is placed through a chain of
        # float transforms, so even a pair moving rigidly (bound 0) changes by about 1e-6 m.
        assert np.all(change <= bound + 1e-5), float(np.max(change - bound))
        moving = bound > 0.0
        largest_share = max(largest_share, float(np.max(change[moving] / bound[moving], initial=0.0)))
        compared += int(both.sum())
    assert compared > 500
    assert largest_share > 0.2  # the bound is not vacuous: some pair moves a good share of it


def _segments(robot: Robot, count: int, seed: int) -> list[np.ndarray]:
    """Straight runs between random configurations, states at the judge's resolution."""
    rng = np.random.default_rng(seed)
    runs = []
    for _ in range(count):
        start = rng.uniform(robot.lower, robot.upper)
        end = np.clip(start + rng.uniform(-0.6, 0.6, robot.dof), robot.lower, robot.upper)
        states = int(np.ceil(np.linalg.norm(end - start) / JUDGE_RESOLUTION_RAD)) + 1
        runs.append(start + np.linspace(0.0, 1.0, states)[:, np.newaxis] * (end - start))
    return runs


@pytest.mark.parametrize("holding", [False, True])
def test_the_scan_finds_what_measuring_every_state_finds(
    panda_scene: tuple[Scene, Robot], holding: bool
) -> None:
    scene, robot = panda_scene
    allowed = [AllowedContact("sugar", robot_links=frozenset(robot.gripper_links))] if holding else []
    # A kept clearance counts only when broken (negative), as an intended contact does; the arm
    # often comes within 0.2 m of the box, so the scan meets such pairs between 0 and its threshold.
    kept = [] if holding else [KeptClearance("sugar", 0.2)]
    if holding:
        _hold_sugar(scene, robot)
    checker = make_collision_checker(scene, robot, allowed, kept=kept)
    colliding = free = skipped = 0
    for qs in _segments(robot, 12, 11 + holding):
        expected = LowestClearance.of(checker.min_clearance(qs))
        for ceiling in (np.inf, 0.0, expected.value + 0.003, max(expected.value - 0.003, 0.0)):
            found = checker.lowest_clearance(qs, ceiling)
            assert found.first_collision == expected.first_collision
            if expected.value < ceiling:
                assert (found.index, found.value) == (expected.index, expected.value)
            else:
                assert found.value >= ceiling
            skipped += len(qs) - found.measured
        until = checker.lowest_clearance(qs, 0.0, until_collision=True)
        assert until.first_collision == expected.first_collision
        valid = checker.is_valid(qs)  # the small-horizon check agrees on where the first collision is
        assert until.first_collision == (None if valid.all() else int(np.argmin(valid)))
        colliding += expected.first_collision is not None
        free += expected.first_collision is None
    assert colliding and free  # both kinds of run were met
    assert skipped > 0  # and the scan measured fewer states than there are


def test_the_scan_finds_what_measuring_every_state_finds_while_the_drawer_slides(
    panda_scene: tuple[Scene, Robot],
) -> None:
    """The hand pulling the drawer: its slide is one more joint of the scan (a box rides inside)."""
    scene, robot = panda_scene
    kitchen = sugar_riding_in_drawer(scene)
    checker = make_collision_checker(scene, robot)
    joint = kitchen.joint("drawer_joint")
    # Runs of the arm moving, and runs of the arm still where the drawer's travel changes its
    # clearance by centimetres (the slide alone decides what the scan may skip there).
    rng = np.random.default_rng(5)
    still = []
    while len(still) < 4:
        q = rng.uniform(robot.lower, robot.upper)
        ends = [checker.min_clearance_along(q[np.newaxis], kitchen, ["drawer_joint"], [[v]])[0]
                for v in (joint.lower, joint.upper)]
        if abs(ends[1] - ends[0]) > 0.03 and min(ends) < 0.3:
            still.append(np.repeat(q[np.newaxis], 150, axis=0))
    colliding = free = skipped = 0
    travel = joint.upper - joint.lower
    for k, qs in enumerate(_segments(robot, 8, 21) + still):
        # out and back, so that a still arm's closest state lies between the states measured first
        openings = joint.lower + travel * np.sin(np.linspace(0.0, np.pi, len(qs)))[:: 1 if k % 2 else -1]
        along = (kitchen, ["drawer_joint"], openings)
        expected = LowestClearance.of(checker.min_clearance_along(qs, *along))
        for ceiling in (np.inf, 0.0, expected.value + 0.003):
            found = checker.lowest_clearance(qs, ceiling, along=along)
            assert found.first_collision == expected.first_collision
            if expected.value < ceiling:
                assert (found.index, found.value) == (expected.index, expected.value)
            skipped += len(qs) - found.measured
        until = checker.lowest_clearance(qs, 0.0, until_collision=True, along=along)
        valid = checker.is_valid_along(qs, *along)
        assert until.first_collision == expected.first_collision
        assert until.first_collision == (None if valid.all() else int(np.argmin(valid)))
        colliding += expected.first_collision is not None
        free += expected.first_collision is None
    assert colliding and free and skipped > 0
