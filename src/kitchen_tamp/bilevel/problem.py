"""A bilevel planning problem: an initial state, an abstraction, a trajectory sampler per abstract action."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, Protocol, TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import Abstraction, AbstractPlanGenerator, AbstractTransition
from kitchen_tamp.bilevel.trajectory import Trajectory

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")


class SamplingFailure(Exception):
    """A trajectory sampler could not realise its abstract transition this time.

    The message says why (``"doorway B-C is blocked by crate"``, ``"no IK solution
    for grasp 3"``); planners count it and record it, then sample again or backtrack.
    ``feedback`` are facts for the abstract level (``kitchen_tamp.bilevel.feedback``): a
    plan generator that learns takes them in.
    """

    def __init__(self, message: str, feedback: tuple[object, ...] = ()) -> None:
        super().__init__(message)
        self.feedback = feedback


class TrajectorySampler(Protocol[X, U, S, A]):
    """Refines one abstract action.

    Given ``state`` with Psi(state) == ``transition.source``, return a trajectory
    starting at ``state`` whose last state abstracts to ``transition.target``, or
    raise :class:`SamplingFailure`. Randomness comes only from ``rng``. The
    sampler must not mutate ``state``: planners may sample from it again.
    """

    def __call__(
        self, state: X, transition: AbstractTransition[S, A], rng: np.random.Generator
    ) -> Trajectory[X, U]: ...


@dataclass(frozen=True)
class BilevelProblem(Generic[X, U, S, A]):
    """Everything a bilevel planner needs.

    ``sampler_for(a)`` returns the trajectory sampler of abstract action ``a``.
    ``plan_generator`` yields abstract plans for SeSamE; when it is ``None`` the
    planners use :func:`~kitchen_tamp.bilevel.abstract_plans.shortest_first_plans`
    over ``abstraction.successors``. ``transition`` is the low-level dynamics
    x' = f(x, u); planners never call it (samplers produce the states), but
    :func:`~kitchen_tamp.bilevel.replay.replay_refined_plan` uses it to re-execute
    a refined plan and check that it reaches the goal.
    """

    initial_state: X
    abstraction: Abstraction[X, S, A]
    sampler_for: Callable[[A], TrajectorySampler[X, U, S, A]]
    transition: Callable[[X, U], X] | None = None
    plan_generator: AbstractPlanGenerator[S, A] | None = None
