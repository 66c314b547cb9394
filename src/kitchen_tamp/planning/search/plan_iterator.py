"""Plans in order of length, for planners that want more than one plan.

``shortest_plans_first`` is a tree search over action sequences (no duplicate
detection across branches, so distinct plans through the same states are all
found) ordered by ``length + remaining``, where ``remaining(state)`` never
overestimates the steps still needed; so goal paths come out in non-decreasing
length. A path never revisits one of its own states, so every plan is acyclic
and the enumeration ends on finite state spaces. Equal lengths are ordered by
an optional seeded random source, else by generation order. It works over any
state and action types: ``iter_plans`` runs it on a grounded ``Task`` with h_max
(shortest first) or h_FF (best first, for large tasks), and the bilevel package's
abstract plan generator on abstract states with exact goal distances.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable, Iterable, Iterator
from typing import Generic, Protocol, TypeVar

from kitchen_tamp.planning.heuristics import HeuristicName, make_heuristic
from kitchen_tamp.planning.task import GroundAction, Task

S = TypeVar("S")
A = TypeVar("A")


class RandomSource(Protocol):
    """Anything with ``random() -> float`` in [0, 1): ``random.Random`` or a numpy ``Generator``."""

    def random(self) -> float: ...


class PathNode(Generic[S, A]):
    """One node of the plan tree: a state and the path that reached it."""

    __slots__ = ("action", "length", "parent", "state")

    def __init__(self, state: S, parent: PathNode[S, A] | None, action: A | None) -> None:
        self.state, self.parent, self.action = state, parent, action
        self.length: int = 0 if parent is None else parent.length + 1

    def visits(self, state: S) -> bool:
        """Whether the path from the root to this node passes through ``state``."""
        node: PathNode[S, A] | None = self
        while node is not None:
            if node.state == state:
                return True
            node = node.parent
        return False

    def path(self) -> tuple[tuple[S, ...], tuple[A, ...]]:
        """The states (root first) and actions along the path to this node."""
        states: list[S] = []
        actions: list[A] = []
        node: PathNode[S, A] | None = self
        while node is not None:
            states.append(node.state)
            if node.action is not None:
                actions.append(node.action)
            node = node.parent
        return tuple(reversed(states)), tuple(reversed(actions))


def shortest_plans_first(
    initial: S,
    successors: Callable[[S], Iterable[tuple[A, S]]],
    is_goal: Callable[[S], bool],
    remaining: Callable[[S], float],
    *,
    rng: RandomSource | None = None,
    max_length: int | None = None,
    max_expansions: int | None = None,
) -> Iterator[tuple[tuple[S, ...], tuple[A, ...]]]:
    """Every acyclic plan from ``initial`` as (states, actions), shortest first (lazily).

    ``remaining(state)``: a lower bound on the steps from ``state`` to a goal,
    ``math.inf`` where none is reachable (those states are never queued). Each
    queued node draws one ``rng.random()`` for its tie-break, the root first,
    so a seeded source gives the same order every run. ``max_expansions`` ends the
    enumeration after that many nodes expanded (over all plans), so a task whose
    plans lie beyond reach (or that has none) does not hold the caller for ever.
    """

    def tie() -> float:
        return rng.random() if rng is not None else 0.0

    if remaining(initial) == math.inf:
        return
    order = itertools.count()
    heap: list[tuple[float, float, int, PathNode[S, A]]] = [
        (remaining(initial), tie(), next(order), PathNode(initial, None, None))]
    expansions = 0
    while heap:
        _, _, _, node = heapq.heappop(heap)
        if is_goal(node.state):
            yield node.path()
            continue  # a plan that passes through a goal state is not a new shortest plan
        if max_length is not None and node.length >= max_length:
            continue
        expansions += 1
        if max_expansions is not None and expansions > max_expansions:
            return
        for action, child in successors(node.state):
            to_go = remaining(child)
            if to_go == math.inf or node.visits(child):
                continue
            bound = node.length + 1 + to_go
            if max_length is not None and bound > max_length:
                continue
            heapq.heappush(heap, (bound, tie(), next(order), PathNode(child, node, action)))


def iter_plans(
    task: Task,
    *,
    rng: RandomSource | None = None,
    max_length: int | None = None,
    heuristic: HeuristicName = "hmax",
    max_expansions: int | None = None,
) -> Iterator[tuple[GroundAction, ...]]:
    """Yield every acyclic plan of ``task`` (lazily: take what you need).

    Ordered by length + ``heuristic``; equal values by ``rng`` if given, else by
    generation order. With h_max (the default) the bound is admissible and plans come
    shortest first. With an informative heuristic that may overestimate (h_FF) they come
    best first instead, as in A* with that heuristic: on a large task the first plan
    comes after a few expansions where h_max's bound leaves the search breadth-first;
    a later plan may be shorter than an earlier one, and ``max_length`` bounds the
    estimate rather than the plans' length. ``max_expansions``: see ``shortest_plans_first``.
    """
    for _, actions in shortest_plans_first(
            task.initial_state, task.successors, task.is_goal, make_heuristic(task, heuristic),
            rng=rng, max_length=max_length, max_expansions=max_expansions):
        yield actions
