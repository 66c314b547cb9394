"""Delete-relaxation heuristics: h_max, h_add and h_FF.

All three come from one exploration of the relaxed task (delete effects and
negative preconditions ignored): a generalised Dijkstra over atoms in which an
action becomes usable once its last precondition is reached, with cost one plus
the max (h_max) or the sum (h_add) of its preconditions' costs. h_FF extracts a
relaxed plan backwards from the goal through the h_add best supporters and
counts its actions.

h_max is admissible (A* with it returns optimal plans); h_add and h_FF are not,
but guide greedy search much better.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable
from typing import Literal

from kitchen_tamp.planning.task import State, Task, bits

INFINITY = float("inf")

HeuristicName = Literal["hmax", "hadd", "hff"]
Heuristic = Callable[[State], float]


class RelaxedExploration:
    """Precomputed structure for fast relaxed explorations of one task."""

    def __init__(self, task: Task) -> None:
        self.task = task
        n_atoms = len(task.atoms)
        self.preconditions_of = [a.pre_ids for a in task.actions]
        self.adds_of = [a.add_ids for a in task.actions]
        self.precondition_count = [len(p) for p in self.preconditions_of]
        self.free_actions = [i for i, count in enumerate(self.precondition_count) if count == 0]
        users: list[list[int]] = [[] for _ in range(n_atoms)]
        for index, pre in enumerate(self.preconditions_of):
            for atom in pre:
                users[atom].append(index)
        self.actions_using = [tuple(u) for u in users]
        self.goal_ids = tuple(bits(task.goal))
        self.n_atoms = n_atoms

    def explore(self, state: State, combine_max: bool) -> tuple[list[float], list[int]]:
        """Cost of every atom from ``state``, and the best supporter of each (-1: none).

        Stops as soon as every goal atom has its final cost.
        """
        cost = [INFINITY] * self.n_atoms
        supporter = [-1] * self.n_atoms
        unsatisfied = self.precondition_count.copy()
        accumulated = [0.0] * len(unsatisfied)
        heap: list[tuple[float, int]] = []
        for atom in bits(state):
            cost[atom] = 0.0
            heap.append((0.0, atom))
        for action in self.free_actions:
            for atom in self.adds_of[action]:
                if cost[atom] > 1.0:
                    cost[atom] = 1.0
                    supporter[atom] = action
                    heap.append((1.0, atom))
        heapq.heapify(heap)
        goals_left = sum(1 for g in self.goal_ids if cost[g] != 0.0)
        is_goal = bytearray(self.n_atoms)
        for g in self.goal_ids:
            is_goal[g] = 1
        done = bytearray(self.n_atoms)
        actions_using, adds_of = self.actions_using, self.adds_of
        heappop, heappush = heapq.heappop, heapq.heappush
        while heap and goals_left:
            atom_cost, atom = heappop(heap)
            if done[atom] or atom_cost > cost[atom]:
                continue
            done[atom] = 1
            if is_goal[atom] and atom_cost > 0.0:
                goals_left -= 1
            for action in actions_using[atom]:
                if combine_max:
                    if atom_cost > accumulated[action]:
                        accumulated[action] = atom_cost
                else:
                    accumulated[action] += atom_cost
                unsatisfied[action] -= 1
                if unsatisfied[action] == 0:
                    new_cost = accumulated[action] + 1.0
                    for added in adds_of[action]:
                        if new_cost < cost[added]:
                            cost[added] = new_cost
                            supporter[added] = action
                            heappush(heap, (new_cost, added))
        return cost, supporter

    def h_max(self, state: State) -> float:
        if self.task.trivially_unsolvable:
            return INFINITY
        cost, _ = self.explore(state, combine_max=True)
        return max((cost[g] for g in self.goal_ids), default=0.0)

    def h_add(self, state: State) -> float:
        if self.task.trivially_unsolvable:
            return INFINITY
        cost, _ = self.explore(state, combine_max=False)
        return sum((cost[g] for g in self.goal_ids), 0.0)

    def relaxed_plan(self, state: State) -> set[int] | None:
        """Indices of the actions of a relaxed plan from ``state``, or None if there is none."""
        if self.task.trivially_unsolvable:
            return None
        cost, supporter = self.explore(state, combine_max=False)
        plan: set[int] = set()
        seen = bytearray(self.n_atoms)
        stack = [g for g in self.goal_ids if cost[g] > 0.0]
        for g in stack:
            if cost[g] == INFINITY:
                return None
        while stack:
            atom = stack.pop()
            if seen[atom]:
                continue
            seen[atom] = 1
            action = supporter[atom]
            if action < 0 or action in plan:
                continue
            plan.add(action)
            stack.extend(p for p in self.preconditions_of[action] if cost[p] > 0.0)
        return plan

    def h_ff(self, state: State) -> float:
        plan = self.relaxed_plan(state)
        return INFINITY if plan is None else float(len(plan))


def make_heuristic(task: Task, name: HeuristicName) -> Heuristic:
    """The named heuristic bound to ``task``."""
    exploration = RelaxedExploration(task)
    heuristics: dict[str, Heuristic] = {
        "hmax": exploration.h_max,
        "hadd": exploration.h_add,
        "hff": exploration.h_ff,
    }
    try:
        return heuristics[name]
    except KeyError:
        raise ValueError(f"unknown heuristic {name!r}; choose from {sorted(heuristics)}") from None
