"""Planning collision models are built once per world and margin and reused: a reused model is
the one a new build would give (same verdicts, same distances), and Drake's model behind the
spheres is built only when the spheres defer to it."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from kitchen_tamp.kitchen import build_kitchen_for_task, sample_action_targets
from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker
from kitchen_tamp.planning import load_task
from kitchen_tamp.refinement.planning_checkers import DeferredDrakeChecker, PlanningCheckers, world_key
from kitchen_tamp.world.scene_description import describe_collision_checker

PROBLEM = Path(__file__).resolve().parents[2] / "pddl" / "problem.pddl"


def test_one_model_per_world_and_margin_whatever_the_arm() -> None:
    task = load_task(PROBLEM)
    opening = task.action_named("open", ["drawer"])
    assert opening is not None
    with build_kitchen_for_task(task) as kitchen:
        targets = sample_action_targets(kitchen, opening, np.random.default_rng(0))
        checkers = PlanningCheckers("spheres")
        first = checkers.checker(kitchen, targets, 0.003)
        assert isinstance(first, SphereScreenedChecker)
        assert isinstance(first.exact, DeferredDrakeChecker) and not first.exact.built
        home = kitchen.arm_configuration()
        kitchen.robot.set_configuration(targets.goal_configuration)
        moved = describe_collision_checker(kitchen.collision_checker())
        kitchen.robot.set_configuration(home)
        same_world = describe_collision_checker(kitchen.collision_checker())
        assert world_key(moved) == world_key(same_world)
        assert checkers.checker(kitchen, targets, 0.003) is first
        assert checkers.checker(kitchen, targets, 0.0) is not first
        assert checkers.built == 2
        fresh = PlanningCheckers("spheres").checker(kitchen, targets, 0.003)
        qs = np.random.default_rng(1).uniform(first.lower, first.upper, size=(300, 7))
        assert np.array_equal(first.is_valid(qs), fresh.is_valid(qs))
        assert isinstance(fresh, SphereScreenedChecker) and fresh.exact_checks > 0
        assert first.exact.built
        q = qs[0]
        assert first.signed_distance(q)[0] == fresh.signed_distance(q)[0]

        kitchen.set_opening("drawer", kitchen.opening_limits("drawer")[1])
        drawer_open = describe_collision_checker(kitchen.collision_checker())
        assert world_key(drawer_open) != world_key(same_world)
