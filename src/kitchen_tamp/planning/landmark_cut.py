"""The LM-cut heuristic (Helmert and Domshlak 2009): admissible, and much closer to h* than h_max.

Each round finds an *action landmark* (a set of actions of which every relaxed
plan uses one) as a cut in the justification graph of h_max, then lowers the
cost of those actions by the cheapest one's and adds that amount to h:

1. h_max of every atom from the state with the current action costs, and each
   action's *precondition choice*: a precondition of largest h_max (an action
   without preconditions hangs from an artificial start atom).
2. The *goal zone*: the goal atom of largest h_max, and every atom from which
   it is reached through actions of cost 0 in the graph of precondition
   choices (choice -> each atom the action adds).
3. The atoms reached from the state in that graph without entering the goal
   zone; the cut is the actions whose precondition choice is among them and
   that add an atom of the goal zone.

It stops when h_max of the goal is 0. Costs only go down, so h_max is not
recomputed from scratch after a cut: the lowered atoms are propagated as in
Fast Downward's implementation (only actions whose precondition choice went
down are looked at again). Costs are unit at the start, as in the task.
"""

from __future__ import annotations

import heapq
from typing import TYPE_CHECKING

from kitchen_tamp.planning.heuristics import INFINITY
from kitchen_tamp.planning.task import bits

if TYPE_CHECKING:
    from kitchen_tamp.planning.heuristics import RelaxedExploration
    from kitchen_tamp.planning.task import State

UNREACHED = 1 << 60
"""h_max of an atom not (yet) reached: larger than any sum of costs."""

START = -1
"""The precondition choice of an action without preconditions: the artificial start atom."""


class LandmarkCut:
    """LM-cut over the goal-relevant actions of one task; call it with a state."""

    def __init__(self, exploration: RelaxedExploration) -> None:
        self.unsolvable = exploration.unsolvable
        self.n_atoms = exploration.n_atoms
        self.preconditions = exploration.preconditions_of
        self.adds = exploration.adds_of
        self.add_masks = exploration.add_masks
        self.users = exploration.relevant_users
        self.achievers = exploration.achievers
        self.goal_ids = exploration.goal_ids
        self.free_actions = exploration.relevant_free_actions
        self.unit_costs = [1] * len(self.preconditions)
        self.unsettled = [len(p) for p in self.preconditions]

    def __call__(self, state: State) -> float:
        if self.unsolvable:
            return INFINITY
        cost = self.unit_costs.copy()
        hmax, choice = self._h_max(state, cost)
        goal_value, top_goal = max((hmax[g], g) for g in self.goal_ids) if self.goal_ids else (0, -1)
        if goal_value >= UNREACHED:
            return INFINITY
        h = 0
        while goal_value > 0:
            cut = self._cut(state, hmax, choice, cost, top_goal)
            lowest = min(cost[action] for action in cut)
            h += lowest
            for action in cut:
                cost[action] -= lowest
            self._lower(cut, hmax, choice, cost)
            goal_value, top_goal = max((hmax[g], g) for g in self.goal_ids)
        return float(h)

    def _h_max(self, state: State, cost: list[int]) -> tuple[list[int], list[int]]:
        """h_max of every atom and every reached action's precondition choice (-2: not reached)."""
        hmax = [UNREACHED] * self.n_atoms
        choice = [-2] * len(self.preconditions)
        unsettled = self.unsettled.copy()
        heap: list[tuple[int, int]] = []
        for atom in bits(state):
            hmax[atom] = 0
            heap.append((0, atom))
        adds, users = self.adds, self.users
        for action in self.free_actions:
            choice[action] = START
            for added in adds[action]:
                if cost[action] < hmax[added]:
                    hmax[added] = cost[action]
                    heapq.heappush(heap, (cost[action], added))
        while heap:
            value, atom = heapq.heappop(heap)
            if value != hmax[atom]:
                continue  # offered again at a lower value, and settled then
            for action in users[atom]:
                unsettled[action] -= 1
                if unsettled[action]:
                    continue
                choice[action] = atom  # settled last, so a precondition of largest h_max
                offer = value + cost[action]
                for added in adds[action]:
                    if offer < hmax[added]:
                        hmax[added] = offer
                        heapq.heappush(heap, (offer, added))
        return hmax, choice

    def _cut(self, state: State, hmax: list[int], choice: list[int], cost: list[int],
             top_goal: int) -> list[int]:
        """The actions from the state's side of the justification graph into the goal zone."""
        goal_zone = 1 << top_goal
        stack = [top_goal]
        achievers = self.achievers
        while stack:
            atom = stack.pop()
            for action in achievers[atom]:
                source = choice[action]
                if cost[action] == 0 and source >= 0 and not goal_zone >> source & 1:
                    goal_zone |= 1 << source
                    stack.append(source)
        before = state
        stack = list(bits(state))
        cut: list[int] = []
        add_masks, users = self.add_masks, self.users
        for action in self.free_actions:
            before = self._cross(action, goal_zone, before, stack, cut)
        while stack:
            atom = stack.pop()
            for action in users[atom]:
                if choice[action] == atom:
                    if add_masks[action] & goal_zone:
                        cut.append(action)
                        continue
                    new = add_masks[action] & ~before
                    if new:
                        before |= new
                        stack.extend(bits(new))
        return cut

    def _cross(self, action: int, goal_zone: int, before: int, stack: list[int], cut: list[int]) -> int:
        """A start action into the cut, or its new atoms onto ``stack``; ``before`` grown."""
        adds = self.add_masks[action]
        if adds & goal_zone:
            cut.append(action)
            return before
        new = adds & ~before
        stack.extend(bits(new))
        return before | new

    def _lower(self, cut: list[int], hmax: list[int], choice: list[int], cost: list[int]) -> None:
        """Propagate the lowered costs of ``cut`` through h_max and the precondition choices."""
        heap: list[tuple[int, int]] = []
        adds, users, preconditions = self.adds, self.users, self.preconditions
        for action in cut:
            offer = (0 if choice[action] == START else hmax[choice[action]]) + cost[action]
            for added in adds[action]:
                if offer < hmax[added]:
                    hmax[added] = offer
                    heapq.heappush(heap, (offer, added))
        while heap:
            value, atom = heapq.heappop(heap)
            if value != hmax[atom]:
                continue
            for action in users[atom]:
                if choice[action] != atom:
                    continue
                best = max(preconditions[action], key=hmax.__getitem__)
                choice[action] = best
                offer = hmax[best] + cost[action]
                for added in adds[action]:
                    if offer < hmax[added]:
                        hmax[added] = offer
                        heapq.heappush(heap, (offer, added))
