"""Re-execute a refined plan through the problem's own dynamics, independently of the samplers."""

from __future__ import annotations

from typing import TypeVar

from kitchen_tamp.bilevel.problem import BilevelProblem
from kitchen_tamp.bilevel.results import RefinedPlan
from kitchen_tamp.bilevel.trajectory import Trajectory, rollout

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")


def replay_refined_plan(
    problem: BilevelProblem[X, U, S, A], plan: RefinedPlan[X, U, S, A]
) -> Trajectory[X, U]:
    """The trajectory that the plan's actions produce from the problem's initial state."""
    if problem.transition is None:
        raise ValueError("the problem has no transition function to replay with")
    return rollout(problem.transition, problem.initial_state, plan.trajectory.actions)


def plan_reaches_goal(problem: BilevelProblem[X, U, S, A], plan: RefinedPlan[X, U, S, A]) -> bool:
    """Replayed step by step, every step ends in its abstract target and the last in an abstract goal."""
    if problem.transition is None:
        raise ValueError("the problem has no transition function to replay with")
    abstract_state = problem.abstraction.abstract_state
    state = problem.initial_state
    if abstract_state(state) != plan.abstract_plan.states[0]:
        return False
    for step in plan.steps:
        state = rollout(problem.transition, state, step.trajectory.actions).final_state
        if abstract_state(state) != step.transition.target:
            return False
    return problem.abstraction.is_goal(abstract_state(state))
