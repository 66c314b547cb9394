"""Abstract plans shortest first, over any abstract successor function.

The reachable abstract graph is explored once (breadth-first, up to
``max_abstract_states``) and every state's exact distance to a goal is computed
backwards over it. Plans are then enumerated by a tree search over action
sequences ordered by ``length + distance to goal``: since that distance never
overestimates what a path still needs, plans come out in non-decreasing
length, and only states that can still reach a goal are ever expanded. A path
never revisits one of its own abstract states, so every plan is acyclic and the
enumeration ends. Plans of equal length are ordered by the seeded RNG.

When the reachable graph is larger than ``max_abstract_states`` the distances
are unknown and the search is uniform-cost (every distance taken as 0).
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from typing import Generic, TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import AbstractPlan, AbstractPlanGenerator

S = TypeVar("S")
A = TypeVar("A")

DEFAULT_MAX_ABSTRACT_STATES = 100_000


class _PathNode(Generic[S, A]):
    """One node of the plan tree: an abstract state and the path that reached it."""

    __slots__ = ("action", "length", "parent", "state")

    def __init__(self, state: S, parent: _PathNode[S, A] | None, action: A | None) -> None:
        self.state, self.parent, self.action = state, parent, action
        self.length: int = 0 if parent is None else parent.length + 1

    def visits(self, state: S) -> bool:
        node: _PathNode[S, A] | None = self
        while node is not None:
            if node.state == state:
                return True
            node = node.parent
        return False

    def plan(self) -> AbstractPlan[S, A]:
        states: list[S] = []
        actions: list[A] = []
        node: _PathNode[S, A] | None = self
        while node is not None:
            states.append(node.state)
            if node.action is not None:
                actions.append(node.action)
            node = node.parent
        return AbstractPlan(tuple(reversed(states)), tuple(reversed(actions)))


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

        order = itertools.count()
        root: _PathNode[S, A] = _PathNode(initial, None, None)
        if distance(initial) == math.inf:
            return
        heap: list[tuple[float, float, int, _PathNode[S, A]]] = [
            (distance(initial), float(rng.random()), next(order), root)]
        while heap:
            _, _, _, node = heapq.heappop(heap)
            if is_goal(node.state):
                yield node.plan()
                continue  # a path through a goal is never a new shortest plan
            if max_length is not None and node.length >= max_length:
                continue
            for action, child in successors(node.state):
                remaining = distance(child)
                if remaining == math.inf or node.visits(child):
                    continue
                bound = node.length + 1 + remaining
                if max_length is not None and bound > max_length:
                    continue
                child_node = _PathNode(child, node, action)
                heapq.heappush(heap, (bound, float(rng.random()), next(order), child_node))

    return generate
