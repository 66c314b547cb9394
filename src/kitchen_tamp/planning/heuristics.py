"""Delete-relaxation heuristics: h_max, h_add and h_FF.

All three explore the relaxed task (delete effects and negative preconditions
ignored). With unit costs, h_max and h_FF need only the relaxed planning graph:
layer by layer, every action whose preconditions are all reached fires at once,
which is a handful of bitset operations per action and layer. h_max is the
index of the first layer holding the whole goal; h_FF extracts a relaxed plan
backwards from the goal, choosing for each subgoal an achiever from the layer
before the subgoal first appears (as in Hoffmann and Nebel's FF), and counts
its actions. h_add needs real sums, so it runs a generalised Dijkstra over
atoms in which an action becomes usable once its last precondition is reached.

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
        self.pre_masks = [a.pre for a in task.actions]
        self.add_masks = [a.add for a in task.actions]
        self.all_actions = list(range(len(task.actions)))

    def explore(self, state: State, combine_max: bool) -> tuple[list[float], list[int]]:
        """h_add/h_max cost of every atom from ``state`` and its best supporter (-1: none).

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

    def layers(self, state: State) -> tuple[list[int], list[list[int]]] | None:
        """The relaxed planning graph from ``state`` up to the first layer with the goal.

        Returns the atoms new in each layer (layer 0 is ``state``) and the actions
        first applicable in each layer, or None if the goal is relaxed-unreachable.
        """
        goal = self.task.goal
        reached = state
        new_atoms = [state]
        new_actions: list[list[int]] = []
        pending = self.all_actions
        pre, add = self.pre_masks, self.add_masks
        while reached & goal != goal:
            fired: list[int] = []
            waiting: list[int] = []
            added = 0
            for action in pending:
                if pre[action] & reached == pre[action]:
                    fired.append(action)
                    added |= add[action]
                else:
                    waiting.append(action)
            added &= ~reached
            if not added:
                return None
            new_actions.append(fired)
            new_atoms.append(added)
            reached |= added
            pending = waiting
        return new_atoms, new_actions

    def h_max(self, state: State) -> float:
        if self.task.trivially_unsolvable:
            return INFINITY
        graph = self.layers(state)
        return INFINITY if graph is None else float(len(graph[0]) - 1)

    def h_add(self, state: State) -> float:
        if self.task.trivially_unsolvable:
            return INFINITY
        cost, _ = self.explore(state, combine_max=False)
        return sum((cost[g] for g in self.goal_ids), 0.0)

    def relaxed_plan(self, state: State) -> list[int] | None:
        """Indices of the actions of a relaxed plan from ``state``, or None if there is none."""
        if self.task.trivially_unsolvable:
            return None
        graph = self.layers(state)
        if graph is None:
            return None
        new_atoms, new_actions = graph
        top = len(new_atoms) - 1
        goals_at = [self.task.goal & atoms for atoms in new_atoms]
        true_at = [0] * (top + 1)
        pre, add = self.pre_masks, self.add_masks
        plan: list[int] = []
        for level in range(top, 0, -1):
            open_goals = goals_at[level] & ~true_at[level]
            while open_goals:
                goal_bit = open_goals & -open_goals
                achiever = next(a for a in new_actions[level - 1] if add[a] & goal_bit)
                plan.append(achiever)
                needs = pre[achiever]
                for below in range(1, level):
                    goals_at[below] |= needs & new_atoms[below]
                true_at[level] |= add[achiever]
                true_at[level - 1] |= add[achiever]
                open_goals &= ~add[achiever]
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
