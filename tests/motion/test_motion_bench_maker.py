"""MotionBenchMaker's problem files (MoveIt YAML) read into a described scene: three problems
written out here in the files' own format, trimmed to a few obstacles."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.motion.geometry.described_scene import DescribedScene
from kitchen_tamp.motion.geometry.primitive_scene import OBSTACLES_BODY, obstacle_links
from kitchen_tamp.motion.geometry.urdf import read_urdf
from kitchen_tamp.motion.motion_bench_maker import (
    MBM_PANDA_LOWER,
    MBM_PANDA_UPPER,
    MbmFormatError,
    mbm_scene,
    read_mbm_problem,
)
from kitchen_tamp.world import panda_urdf_path

ACM = """allowed_collision_matrix:
  entry_names: [panda_hand, panda_leftfinger, panda_link0, panda_link5]
  entry_values:
    - [false, true, false, false]
    - [true, false, false, true]
    - [false, false, false, false]
    - [false, true, false, false]
"""

TABLE_SCENE = (
    """robot_model_name: panda
world:
  collision_objects:
    - primitive_poses:
        - position: [0.3, 0.84, 0.3]
          orientation: [0, 0, 0.4966790222940755, 0.8679342998251661]
      primitives:
        - dimensions: [0.12, 0.03]
          type: cylinder
      id: Can1
    - id: table_top
      primitives:
        - type: box
          dimensions: [1.2, 0.6, 0.04]
      primitive_poses:
        - position: [0.2, 0.9, 0.22]
          orientation: [0, 0, 0, 1]
    - id: Wall
      primitives:
        - type: box
          dimensions: [0.08, 0.08, 1.2]
      primitive_poses:
        - position: [0.45, 0.25, 0.6]
          orientation: [0, 0, 0, 1]
    - id: Ball
      primitives:
        - type: sphere
          dimensions: [0.05]
      primitive_poses:
        - position: [0.5, 0.6, 0.5]
          orientation: [0, 0, 0, 1]
"""
    + ACM
)

TABLE_REQUEST = """start_state:
  joint_state:
    name: [panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5, panda_joint6,
           panda_joint7, panda_finger_joint1, panda_finger_joint2]
    position: [0, -0.785, 0, -2.356, 0, 1.571, 0.785, 0.065, 0.065]
goal_constraints:
  - joint_constraints:
      - joint_name: panda_joint1
        position: 1.2
      - position: 0.2
        joint_name: panda_joint2
      - joint_name: panda_joint3
        position: 0.1
      - position: -1.9
        joint_name: panda_joint4
      - joint_name: panda_joint5
        position: 0.0
      - position: 2.1
        joint_name: panda_joint6
      - joint_name: panda_joint7
        position: 0.8
"""

SHELF_SCENE = (
    """world:
  collision_objects:
    - id: shelf
      pose:
        position: [0.8, 0, 0]
        orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]
      primitives:
        - type: box
          dimensions: [0.6, 0.3, 0.02]
        - type: box
          dimensions: [0.6, 0.3, 0.02]
      primitive_poses:
        - position: [0, 0, 0.4]
          orientation: [0, 0, 0, 1]
        - position: [0, 0, 0.8]
          orientation: [0, 0, 0, 1]
"""
    + ACM
)


def test_a_scene_and_request_become_start_goal_obstacles_and_self_pairs() -> None:
    problem = read_mbm_problem("table_pick", 7, TABLE_SCENE, TABLE_REQUEST)
    assert problem.name == "table_pick-0007"
    assert np.allclose(problem.start, [0, -0.785, 0, -2.356, 0, 1.571, 0.785])
    assert np.allclose(problem.goals, [[1.2, 0.2, 0.1, -1.9, 0.0, 2.1, 0.8]])
    can, top, _, ball = problem.obstacles
    assert (can.kind, top.kind, ball.kind) == ("cylinder", "box", "sphere")
    assert np.allclose(can.size, [0.03, 0.12])  # MoveIt gives (height, radius)
    assert np.allclose(top.size, [1.2, 0.6, 0.04]) and np.allclose(ball.size, [0.05])
    angle = 2 * np.arctan2(0.4966790222940755, 0.8679342998251661)
    assert np.allclose(can.world_from_shape[:3, :3] @ [1, 0, 0], [np.cos(angle), np.sin(angle), 0])
    assert np.allclose(can.world_from_shape[:3, 3], [0.3, 0.84, 0.3])
    # The matrix's false entries: hand-link0, hand-link5, finger-link0, link0-link5.
    assert set(problem.self_pairs) == {
        ("panda_hand", "panda_link0"),
        ("panda_hand", "panda_link5"),
        ("panda_leftfinger", "panda_link0"),
        ("panda_link0", "panda_link5"),
    }


def test_primitives_are_placed_relative_to_their_object_pose() -> None:
    problem = read_mbm_problem("bookshelf_small", 1, SHELF_SCENE, TABLE_REQUEST)
    lower, upper = problem.obstacles
    assert (lower.name, upper.name) == ("shelf_0", "shelf_1")
    assert np.allclose(upper.world_from_shape[:3, 3], [0.8, 0.0, 0.8])
    assert np.allclose(upper.world_from_shape[:3, :3] @ [1, 0, 0], [0, 1, 0])


def test_the_described_scene_writes_every_obstacle_where_the_file_puts_it(tmp_path: Path) -> None:
    problem = read_mbm_problem("table_pick", 7, TABLE_SCENE, TABLE_REQUEST)
    scene = mbm_scene(problem, panda_urdf_path(), tmp_path)
    robot, obstacles = scene.bodies
    assert robot.joint_positions["panda_finger_joint1"] == pytest.approx(0.065)
    assert np.array_equal(scene.arm_lower, MBM_PANDA_LOWER) and np.array_equal(
        scene.arm_upper, MBM_PANDA_UPPER
    )
    model = read_urdf(obstacles.urdf_path)
    links = obstacle_links(problem.obstacles)
    for link, obstacle in zip(links, problem.obstacles, strict=True):
        joint = model.joint_to(link)
        assert joint is not None and np.allclose(joint.origin, obstacle.world_from_shape, atol=1e-12)
        (shape,) = [s for s in model.collisions if s.link == link]
        assert shape.kind == obstacle.kind and np.allclose(shape.size, obstacle.size)
    pairs = {(p.link_a, p.body_b, p.link_b) for p in scene.checked_pairs}
    assert ("panda_hand", OBSTACLES_BODY, links[0]) in pairs
    assert ("panda_hand", "panda", "panda_link5") in pairs
    assert ("panda_link3", "panda", "panda_hand") not in pairs  # the matrix allows it


@pytest.mark.parametrize(
    ("scene", "request_text", "message"),
    [
        (
            TABLE_SCENE.replace("type: sphere", "type: cone"),
            TABLE_REQUEST,
            "scene.yaml: world.collision_objects[3]",
        ),
        (TABLE_SCENE.replace("dimensions: [0.05]", "dimensions: [0.05, 1]"), TABLE_REQUEST, "expected 1"),
        (
            TABLE_SCENE,
            TABLE_REQUEST.replace("joint_name: panda_joint7", "joint_name: panda_joint8"),
            "panda_joint7",
        ),
        (TABLE_SCENE.replace("world:", "globe:"), TABLE_REQUEST, "missing key 'world'"),
        (TABLE_SCENE, "start_state: [unclosed", "request.yaml: line"),
    ],
)
def test_a_malformed_file_is_named_with_its_key(scene: str, request_text: str, message: str) -> None:
    where = {"scene": "scene.yaml", "request": "request.yaml"}
    with pytest.raises(MbmFormatError, match=message.replace("[", r"\[").replace("]", r"\]")):
        read_mbm_problem("table_pick", 1, scene, request_text, where)


@pytest.mark.slow
def test_a_problem_is_planned_with_the_spheres_and_the_path_is_free_for_drake(tmp_path: Path) -> None:
    from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
    from kitchen_tamp.motion import ConfigurationSpace, densify_path, plan_rrt_connect, shortcut_path
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
    from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker

    problem = read_mbm_problem("table_pick", 7, TABLE_SCENE, TABLE_REQUEST)
    scene = mbm_scene(problem, panda_urdf_path(), tmp_path)
    spheres, exact = SphereCollisionChecker(scene), DrakeCollisionChecker(scene)
    space = ConfigurationSpace(MBM_PANDA_LOWER, MBM_PANDA_UPPER)
    # bounded by iterations, not by the clock: a loaded machine must not fail the test
    start, goal = problem.start, problem.goals[0]
    planned = plan_rrt_connect(start, goal, space, spheres, seed=3, time_budget_s=math.inf)
    assert planned.path is not None
    path = shortcut_path(planned.path, spheres, seed=3, time_budget_s=math.inf).path
    assert np.allclose(path[0], problem.start) and np.allclose(path[-1], problem.goals[0])
    assert np.all(exact.is_valid(densify_path(path, JUDGE_RESOLUTION_RAD)))
    straight = densify_path(np.stack([problem.start, problem.goals[0]]), 0.01)
    assert not np.all(exact.is_valid(straight))  # the wall makes it a detour


def _table_scene_with_ball(centre: np.ndarray, radius: float, directory: Path) -> DescribedScene:
    """The table problem's scene with its ball moved to ``centre`` and given ``radius``."""
    x, y, z = (float(v) for v in centre)
    text = TABLE_SCENE.replace("position: [0.5, 0.6, 0.5]", f"position: [{x!r}, {y!r}, {z!r}]")
    text = text.replace("dimensions: [0.05]", f"dimensions: [{float(radius)!r}]")
    directory.mkdir()
    return mbm_scene(read_mbm_problem("table_pick", 7, text, TABLE_REQUEST), panda_urdf_path(), directory)


@pytest.mark.slow
def test_a_goal_within_the_spheres_slack_is_planned_to_with_drake_confirming_near_it(tmp_path: Path) -> None:
    from kitchen_tamp.joint_spacing import JUDGE_RESOLUTION_RAD
    from kitchen_tamp.motion import (
        ConfigurationSpace,
        PlanStatus,
        densify_path,
        plan_rrt_connect,
        shortcut_path,
    )
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
    from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
    from kitchen_tamp.motion.geometry.spheres.screening import EndConfirmedChecker

    problem = read_mbm_problem("table_pick", 7, TABLE_SCENE, TABLE_REQUEST)
    start, goal = problem.start, problem.goals[0]
    tree = SphereCollisionChecker(mbm_scene(problem, panda_urdf_path(), tmp_path / "plain")).model.tree
    hand = tree.link_poses(goal[np.newaxis])[0, tree.link_index["panda_hand"], :3, 3]
    # a ball beside the hand, grown until Drake finds the goal 2 mm from it
    centre, probe_radius, clearance = hand + np.array([0.12, 0.0, -0.1]), 0.02, 0.002
    gap = DrakeCollisionChecker(
        _table_scene_with_ball(centre, probe_radius, tmp_path / "probe")
    ).min_distance(goal)
    scene = _table_scene_with_ball(centre, probe_radius + gap - clearance, tmp_path / "near")
    spheres, exact = SphereCollisionChecker(scene), DrakeCollisionChecker(scene)
    assert exact.min_distance(goal) == pytest.approx(clearance, abs=1e-4)
    assert not spheres.is_valid_without_padding(goal[np.newaxis])[0]  # within the spheres' slack
    space = ConfigurationSpace(MBM_PANDA_LOWER, MBM_PANDA_UPPER)
    alone = plan_rrt_connect(start, goal, space, spheres, seed=3, time_budget_s=math.inf)
    assert alone.status is PlanStatus.GOAL_IN_COLLISION

    confirmed = EndConfirmedChecker(spheres, exact, [start, goal], exact_is_bare=True)
    assert np.array_equal(confirmed.ends, goal[np.newaxis])  # the start is clear for the spheres
    planned = plan_rrt_connect(start, goal, space, confirmed, seed=3, time_budget_s=math.inf)
    assert planned.path is not None
    path = shortcut_path(planned.path, confirmed, seed=3, time_budget_s=math.inf).path
    assert np.allclose(path[0], start) and np.allclose(path[-1], goal)
    assert np.all(exact.is_valid(densify_path(path, JUDGE_RESOLUTION_RAD)))
    assert confirmed.screened.exact_checks > 0
