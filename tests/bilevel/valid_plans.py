"""What makes a refined toy rooms plan valid: replayed through the dynamics it reaches the goal
room, and its path never touches an obstacle."""

from __future__ import annotations

from kitchen_tamp.bilevel import BilevelProblem, RefinedPlan, plan_reaches_goal
from kitchen_tamp.bilevel.toy_rooms import Passage, Point, RoomsScene


def assert_valid_toy_plan(scene: RoomsScene, problem: BilevelProblem[Point, Point, str, Passage],
                          plan: RefinedPlan[Point, Point, str, Passage] | None) -> None:
    assert plan is not None
    assert plan_reaches_goal(problem, plan)
    assert scene.world.room_at(plan.final_state) == scene.world.room(scene.goal_room)
    assert scene.world.path_hit(plan.trajectory.states) is None
