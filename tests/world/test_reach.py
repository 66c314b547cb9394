"""The reach test before IK: it never turns away a pose the arm reaches, it turns away poses no
configuration reaches, and turning one away draws from the generator what a failed IK draws."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.world import InverseKinematics, Pose, Robot, Scene
from kitchen_tamp.world.reach import arm_reach
from kitchen_tamp.world.transforms import rotation_about_axis

# The tool pointing back at the robot from 0.63 m in front of it: a grasp from the far side of
# a box on the counter, which the skills propose and no configuration reaches.
FACING_BACK = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])


def test_the_pandas_shoulder_wrist_and_reach(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    reach = arm_reach(robot, 1e-3, 1e-2)
    assert reach is not None
    shoulder = robot.body.base_pose().apply(reach.base_from_shoulder)
    for link in ("panda_link1", "panda_link2"):
        assert np.allclose(robot.forward_kinematics(robot.mid_configuration(), link).position, shoulder)
    # the datasheet's offsets from joint 2 to the wrist: 0.316, 0.0825, and 0.384 beside 0.0825
    assert abs(reach.reach_m - (0.316 + 0.0825 + np.hypot(0.384, 0.0825))) < 1e-4
    assert abs(reach.circle_radius - 0.088) < 1e-4


def test_no_reachable_pose_is_turned_away(panda_scene: tuple[Scene, Robot]) -> None:
    """Tool poses of configurations drawn within the limits, and the same poses moved by IK's
    tolerances, all pass: the test is sound."""
    _, robot = panda_scene
    ik = InverseKinematics(robot)
    reach = ik.reach
    assert reach is not None
    base = robot.body.base_pose()
    rng = np.random.default_rng(7)
    closest = np.inf
    for _ in range(1500):
        pose = robot.forward_kinematics(rng.uniform(robot.lower, robot.upper))
        axis = rng.normal(size=3)
        turn = rotation_about_axis(axis / np.linalg.norm(axis), ik.options.orientation_tolerance)
        shift = rng.normal(size=3)
        moved = Pose.from_rotation(
            np.asarray(pose.position) + ik.options.position_tolerance * shift / np.linalg.norm(shift),
            turn @ pose.rotation,
        )
        for target in (pose, moved):
            assert not reach.beyond(base, target)
            closest = min(closest, reach.reach_m + reach.slack_m - reach.wrist_distance(base, target))
    assert closest >= 0.0


def test_a_pose_facing_back_from_the_far_side_is_beyond_reach(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    ik = InverseKinematics(robot)
    base = robot.body.base_pose().position
    target = Pose.from_rotation((base[0] + 0.63, base[1] - 0.23, base[2] + 0.45), FACING_BACK)
    assert ik.reach is not None and ik.reach.beyond(robot.body.base_pose(), target)
    # ... and IK agrees: no start reaches it
    ik.reach = None
    assert ik.solve(target, np.random.default_rng(0)) is None


def test_a_pose_turned_away_draws_what_a_failed_ik_draws(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    base = robot.body.base_pose().position
    target = Pose.from_rotation((base[0] + 0.63, base[1] - 0.23, base[2] + 0.45), FACING_BACK)
    with_test, without_test = InverseKinematics(robot), InverseKinematics(robot)
    without_test.reach = None
    first, second = np.random.default_rng(5), np.random.default_rng(5)
    before = robot.configuration()
    assert with_test.solve(target, first, seeds=[before]) is None
    assert without_test.solve(target, second, seeds=[before]) is None
    assert with_test.beyond_reach == 1 and without_test.beyond_reach == 0
    assert np.array_equal(first.random(4), second.random(4))
    assert np.array_equal(robot.configuration(), before)
