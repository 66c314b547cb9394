"""Abstract plans shortest first, over any abstract successor function.

The reachable abstract graph is explored once (breadth-first, up to
``max_abstract_states``) and every state's exact distance to a goal is computed
backwards over it. Plans are then enumerated by the planning package's
``shortest_plans_first`` (a tree search over action sequences ordered by
``length + distance to goal``, see ``planning.search.plan_iterator``): plans come
out in non-decreasing length, only states that can still reach a goal are ever
expanded, and every plan is acyclic. Plans of equal length are ordered by the
seeded RNG.

When the reachable graph is larger than ``max_abstract_states`` the distances
are unknown and the search is uniform-cost (every distance taken as 0).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from typing import TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import AbstractPlan, AbstractPlanGenerator
from kitchen_tamp.planning import shortest_plans_first

S = TypeVar("S")
A = TypeVar("A")

DEFAULT_MAX_ABSTRACT_STATES = 100_000


def goal_distances(
    initial: S,
    successors: Callable[[S], Iterable[tuple[A, S]]],
    is_goal: Callable[[S], bool],
    max_abstract_states: int = DEFAULT_MAX_ABSTRACT_STATES,
) -> dict[S, int] | None:
    """Steps from each reachable abstract state to the nearest goal (absent: none reachable).

    ``None`` when more than ``max_abstract_states`` states are reachable.
    """
    predecessors: dict[S, list[S]] = {initial: []}
    frontier = deque([initial])
    goals: list[S] = []
    while frontier:
        state = frontier.popleft()
        if is_goal(state):
            goals.append(state)
        for _, child in successors(state):
            if child not in predecessors:
                if len(predecessors) >= max_abstract_states:
                    return None
                predecessors[child] = []
                frontier.append(child)
            predecessors[child].append(state)
    distance = dict.fromkeys(goals, 0)
    backward = deque(goals)
    while backward:
        state = backward.popleft()
        for parent in predecessors[state]:
            if parent not in distance:
                distance[parent] = distance[state] + 1
                backward.append(parent)
    return distance


def shortest_first_plans(
    successors: Callable[[S], Iterable[tuple[A, S]]],
    is_goal: Callable[[S], bool],
    *,
    max_length: int | None = None,
    max_abstract_states: int = DEFAULT_MAX_ABSTRACT_STATES,
) -> AbstractPlanGenerator[S, A]:
    """A generator of every acyclic abstract plan, shortest first, ties broken by the RNG it is given."""

    def generate(initial: S, rng: np.random.Generator) -> Iterator[AbstractPlan[S, A]]:
        distances = goal_distances(initial, successors, is_goal, max_abstract_states)

        def distance(state: S) -> float:
            if distances is None:
                return 0.0
            return distances.get(state, math.inf)

        for states, actions in shortest_plans_first(initial, successors, is_goal, distance,
                                                    rng=rng, max_length=max_length):
            yield AbstractPlan(states, actions)

    return generate
