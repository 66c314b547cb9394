"""A sample the judge would reject is a failed sample: refine_action replays every sample it
would accept the judge's way and refuses (leaving the scene untouched) what the judge refuses."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.motion.collision_checker import CollisionChecker, JointConfiguration
from kitchen_tamp.planning import load_task
from kitchen_tamp.refinement.motion_backend import BoundedCollisionChecker, MotionSolution
from kitchen_tamp.refinement.refine_action import refine_action

PROBLEM = Path(__file__).resolve().parents[2] / "pddl" / "problem.pddl"


@dataclass(frozen=True)
class DetourBackend:
    """A back end that hands over a path through ``detour`` without checking it."""

    detour: np.ndarray
    name: str = "detour"

    def solve(
        self,
        start: JointConfiguration,
        goal: JointConfiguration,
        checker: BoundedCollisionChecker,
        strict_checker: CollisionChecker,
        rng: np.random.Generator,
    ) -> MotionSolution:
        return MotionSolution(np.stack([start, self.detour, goal]), "solved", 1)


def test_a_move_the_judge_refuses_is_a_failed_sample() -> None:
    task = load_task(PROBLEM)
    opening = task.action_named("open", ["drawer"])
    assert opening is not None
    with build_kitchen_for_task(task) as kitchen:
        checker = kitchen.collision_checker()
        candidates = np.random.default_rng(0).uniform(checker.lower, checker.upper, size=(200, 7))
        colliding = candidates[~checker.is_valid(candidates)][0]
        before, home = kitchen.scene.save_state(), kitchen.arm_configuration()
        backend = DetourBackend(colliding)
        trajectory, record = refine_action(kitchen, 0, opening, backend, np.random.default_rng(0))
        assert trajectory is None and not record.solved
        rejection = record.rejections[0]
        assert rejection.startswith("the judge's replay of sample 1 rejects it: (open drawer) move: ")
        assert "collision" in record.rejections[0]
        assert np.array_equal(kitchen.arm_configuration(), home)
        assert kitchen.opening("drawer") == kitchen.opening_limits("drawer")[0]
        assert kitchen.scene.save_state().attachments == before.attachments
