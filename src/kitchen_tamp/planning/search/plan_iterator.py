"""Plans in order of length, for planners that want more than one abstract plan.

A tree search over action sequences (no duplicate detection across branches,
so distinct plans through the same states are all found) ordered by
``length + h_max``. Because h_max never overestimates, goal paths come out in
non-decreasing length. A path never revisits one of its own states, so every
plan is acyclic and the enumeration ends on finite tasks. Equal lengths are
ordered by an optional seeded RNG, else by generation order.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Iterator

import numpy as np

from kitchen_tamp.planning.heuristics import INFINITY, make_heuristic
from kitchen_tamp.planning.task import GroundAction, State, Task


class _PathNode:
    __slots__ = ("action", "parent", "state")

    def __init__(self, state: State, parent: _PathNode | None, action: GroundAction | None) -> None:
        self.state, self.parent, self.action = state, parent, action

    def plan(self) -> tuple[GroundAction, ...]:
        steps: list[GroundAction] = []
        node: _PathNode | None = self
        while node is not None and node.action is not None:
            steps.append(node.action)
            node = node.parent
        return tuple(reversed(steps))

    def visits(self, state: State) -> bool:
        node: _PathNode | None = self
        while node is not None:
            if node.state == state:
                return True
            node = node.parent
        return False


def iter_plans(
    task: Task, *, rng: np.random.Generator | None = None, max_length: int | None = None
) -> Iterator[tuple[GroundAction, ...]]:
    """Yield every acyclic plan, shortest first (lazily: take what you need)."""
    h = make_heuristic(task, "hmax")
    h_root = h(task.initial_state)
    if h_root == INFINITY:
        return
    order = itertools.count()

    def tie() -> float:
        return float(rng.random()) if rng is not None else 0.0

    heap: list[tuple[float, float, int, int, _PathNode]] = [
        (h_root, tie(), next(order), 0, _PathNode(task.initial_state, None, None))]
    while heap:
        _, _, _, g, node = heapq.heappop(heap)
        if task.is_goal(node.state):
            yield node.plan()
            continue  # a plan that passes through a goal state is not a new shortest plan
        if max_length is not None and g >= max_length:
            continue
        for action, child in task.successors(node.state):
            if node.visits(child):
                continue
            h_child = h(child)
            if h_child == INFINITY or (max_length is not None and g + 1 + h_child > max_length):
                continue
            heapq.heappush(heap, (g + 1 + h_child, tie(), next(order), g + 1,
                                  _PathNode(child, node, action)))
