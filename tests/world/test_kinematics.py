from __future__ import annotations

from pathlib import Path

import numpy as np

from kitchen_tamp.world import (
    IkOptions,
    InverseKinematics,
    Pose,
    Robot,
    Scene,
    panda_urdf_path,
    straight_line,
)
from kitchen_tamp.world.robot import safety_limits
from tests.world.conftest import down_rotation


def test_fk_ik_round_trip(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    ik = InverseKinematics(robot, IkOptions(restarts=40))
    rng = np.random.default_rng(0)
    before = robot.configuration()
    for _ in range(10):
        q = rng.uniform(robot.lower, robot.upper)
        world_from_tool = robot.forward_kinematics(q)
        solution = ik.solve(world_from_tool, rng)
        assert solution is not None, f"no IK for the tool pose of {q}"
        assert robot.within_limits(solution)
        position_error, angle_error = robot.forward_kinematics(solution).distance_to(world_from_tool)
        assert position_error <= ik.options.position_tolerance
        assert angle_error <= ik.options.orientation_tolerance
    assert np.array_equal(robot.configuration(), before)


def test_ik_is_deterministic_for_a_seed(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    ik = InverseKinematics(robot)
    target = Pose.from_rotation((0.5, 0.1, 0.9), down_rotation())
    first = ik.solve(target, np.random.default_rng(3))
    second = ik.solve(target, np.random.default_rng(3))
    assert first is not None and second is not None
    assert np.array_equal(first, second)


def test_unreachable_pose_has_no_solution(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    ik = InverseKinematics(robot)
    assert ik.solve(Pose.from_rotation((3.0, 0.0, 0.9), down_rotation()), np.random.default_rng(0)) is None


def test_straight_line_follow_keeps_tool_on_the_line(panda_scene: tuple[Scene, Robot]) -> None:
    _, robot = panda_scene
    ik = InverseKinematics(robot)
    start = Pose.from_rotation((0.5, 0.0, 0.9), down_rotation())
    q_start = ik.solve(start, np.random.default_rng(0))
    assert q_start is not None
    waypoints = straight_line(start, (0.0, 0.0, -0.1), 0.01)
    path = ik.follow(q_start, waypoints)
    assert path is not None and len(path) == len(waypoints) + 1
    assert np.max(np.abs(np.diff(path, axis=0))) <= 0.2
    for q, target in zip(path[1:], waypoints, strict=True):
        assert robot.forward_kinematics(q).distance_to(target)[0] <= 1e-3


def test_joint_ranges_are_the_stricter_of_limit_and_safety_controller(
    panda_scene: tuple[Scene, Robot], tmp_path: Path
) -> None:
    _, robot = panda_scene
    soft = safety_limits(Path(panda_urdf_path()))
    names = robot.description.arm_joints
    assert set(names) <= set(soft)
    for i, name in enumerate(names):
        assert robot.lower[i] == max(robot.urdf_lower[i], soft[name][0])
        assert robot.upper[i] == min(robot.urdf_upper[i], soft[name][1])
    assert robot.upper[3] == -0.0698 and robot.urdf_upper[3] == 0.0  # the Panda's joint 4
    assert np.all(robot.lower > robot.urdf_lower) and np.all(robot.upper < robot.urdf_upper)
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot")
    assert safety_limits(broken) == {}
