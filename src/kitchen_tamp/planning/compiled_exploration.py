"""h_add's exploration and h_FF's relaxed plan with helpful actions, through the compiled kernels.

``CompiledExploration`` lays a ``RelaxedExploration``'s tables out as flat int
arrays once per task and answers as its ``additive_costs`` and
``supported_plan`` do (the same costs, supporters, plans and helpful actions),
in a fraction of the time on large tasks. Importing this module imports numpy;
its methods import numba and the kernels (``relaxed_kernel``), about a second
with the kernels read from numba's cache, which a small task never earns back:
``LandmarkEvaluator`` calls them only once it has done enough work in Python
(``COMPILED_AFTER_WORK``). The greedy search through numba's kernel
(``search.compiled_greedy``) reads the arrays laid out here.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from kitchen_tamp.planning.heuristics import BUCKET_LEVELS, INFINITY, RelaxedExploration
from kitchen_tamp.planning.task import State, bits

if TYPE_CHECKING:
    from kitchen_tamp.planning.landmark_count import LandmarkCount
    from kitchen_tamp.planning.relaxed_kernel import ByteArray, IntArray


def _flat(rows: Iterable[Iterable[int]]) -> tuple[IntArray, IntArray]:
    """Rows of ints as one array and the offsets where each row starts (one more than rows, CSR)."""
    starts = [0]
    values: list[int] = []
    for row in rows:
        values.extend(row)
        starts.append(len(values))
    return np.array(starts, dtype=np.int64), np.array(values, dtype=np.int64)


def _bytes_of(mask: int, size: int) -> ByteArray:
    return np.frombuffer(mask.to_bytes(size, "little"), dtype=np.uint8)


def _rows(masks: Iterable[int], size: int) -> ByteArray:
    """Bitsets as the rows of a byte matrix (``size`` bytes each)."""
    return np.array([np.frombuffer(mask.to_bytes(size, "little"), dtype=np.uint8) for mask in masks],
                    dtype=np.uint8).reshape(-1, size)


def _bitset(indices: IntArray) -> int:
    mask = 0
    for index in indices.tolist():
        mask |= 1 << index
    return mask


class CompiledExploration:
    """One task's relaxed exploration as flat arrays, with the work space the kernels fill."""

    def __init__(self, exploration: RelaxedExploration,
                 achievers: Sequence[Sequence[int]] | None = None,
                 bucket_levels: int = BUCKET_LEVELS) -> None:
        """``achievers``: per atom, the actions ``achieving`` looks at (default: relevant ones adding it);
        ``bucket_levels`` (at least 1): the costs h_add's exploration keeps in buckets
        (``relaxed_kernel``)."""
        self.exploration = exploration
        n_atoms, n_actions = exploration.n_atoms, len(exploration.adds_of)
        self.n_atoms = n_atoms
        self.state_bytes = max(1, (n_atoms + 7) // 8)
        self.users_start, self.users = _flat(exploration.relevant_users)
        self.adds_start, self.adds = _flat(exploration.adds_of)
        self.pre_start, self.pres = _flat(exploration.preconditions_of)
        self.precondition_counts = np.array(exploration.relevant_precondition_count, dtype=np.int64)
        self.free_actions = np.array(exploration.relevant_free_actions, dtype=np.int64)
        self.goal_ids = np.array(exploration.goal_ids, dtype=np.int64)
        self.cost = np.empty(n_atoms, dtype=np.int64)
        self.supporter = np.empty(n_atoms, dtype=np.int64)
        self.unsettled = np.empty(n_actions, dtype=np.int64)
        self.settled_sum = np.empty(n_actions, dtype=np.int64)
        offers = n_atoms + len(self.adds) + 1  # every atom of the state, and every add effect offered once
        self.heap = np.empty(offers, dtype=np.int64)
        self.offered_atoms = np.empty(offers, dtype=np.int64)
        self.next_offer = np.empty(offers, dtype=np.int64)
        self.level_first = np.empty(max(1, bucket_levels), dtype=np.int64)
        self.level_last = np.empty(max(1, bucket_levels), dtype=np.int64)
        self.plan = np.empty(n_actions, dtype=np.int64)
        self.helpful = np.empty(n_actions, dtype=np.int64)
        self.chosen = np.zeros(n_actions, dtype=np.uint8)
        self.marked = np.zeros(n_atoms, dtype=np.uint8)
        self.marked_atoms = np.empty(n_atoms, dtype=np.int64)
        self.stack = np.empty(n_atoms + len(self.pres) + 1, dtype=np.int64)
        achievers = exploration.achievers if achievers is None else achievers
        self.achievers_start, self.achievers = _flat(achievers)
        self.neg_start, self.negs = _flat(bits(action.pre_neg) for action in exploration.task.actions)
        self.found = np.empty(len(self.achievers) + 1, dtype=np.int64)

    def _state_array(self, state: State) -> ByteArray:
        return _bytes_of(state, self.state_bytes)

    def explore(self, state: State) -> ByteArray | None:
        """Run h_add's exploration from ``state`` (costs in ``self.cost``): the state's bytes, None at a
        dead end."""
        from kitchen_tamp.planning.relaxed_kernel import additive_exploration

        state_array = self._state_array(state)
        reached = additive_exploration(
            state_array, self.n_atoms, self.users_start, self.users, self.adds_start, self.adds,
            self.precondition_counts, self.free_actions, self.goal_ids, self.cost, self.supporter,
            self.unsettled, self.settled_sum, self.heap, self.offered_atoms, self.level_first,
            self.level_last, self.next_offer)
        return state_array if reached else None

    def plan_and_helpful(self, state_array: ByteArray, targets: IntArray | None = None) -> tuple[int, int]:
        """The size of the best supporters' relaxed plan to ``targets`` (default: the goal) from the last
        exploration, and its actions applicable in the state, as a bitset over action indices."""
        from kitchen_tamp.planning.relaxed_kernel import supported_plan

        length, applicable = supported_plan(
            state_array, self.goal_ids if targets is None else targets, self.cost, self.supporter,
            self.pre_start, self.pres, self.plan, self.helpful, self.chosen, self.marked,
            self.marked_atoms, self.stack)
        return length, _bitset(self.helpful[:applicable])

    def achieving(self, state_array: ByteArray, targets: IntArray) -> int:
        """The actions achieving one of the atoms ``targets`` that are applicable in the state, as a bitset
        (``LandmarkCount.achieving_actions`` with this object's ``achievers``)."""
        from kitchen_tamp.planning.relaxed_kernel import applicable_achievers

        count = applicable_achievers(
            state_array, targets, self.achievers_start, self.achievers, self.pre_start, self.pres,
            self.neg_start, self.negs, self.found)
        return _bitset(self.found[:count])

    def helpful_towards_nearest(self, state_array: ByteArray, atoms: IntArray) -> int:
        """The applicable actions of the relaxed plan to the cheapest of the atoms ``atoms`` (ascending) in
        the last exploration (``LandmarkEvaluator._towards_nearest``), as a bitset; 0 if none is reached."""
        from kitchen_tamp.planning.relaxed_kernel import UNREACHED

        target_costs = self.cost[atoms]
        nearest = target_costs.min(initial=UNREACHED)
        if nearest == UNREACHED:
            return 0
        return self.plan_and_helpful(state_array, atoms[target_costs == nearest])[1]

    def costs(self) -> list[float]:
        """The last exploration's costs as ``RelaxedExploration.additive_costs`` gives them."""
        from kitchen_tamp.planning.relaxed_kernel import UNREACHED

        return [INFINITY if value == UNREACHED else value for value in self.cost.tolist()]

    def supporters(self) -> list[int]:
        """The last exploration's best supporters (-1: none)."""
        return self.supporter.tolist()


class CompiledLandmarkCount:
    """``LandmarkCount.value`` through the compiled kernel: the same h_LM and landmarks to reach next."""

    def __init__(self, count: LandmarkCount, state_bytes: int) -> None:
        self.state_bytes = state_bytes
        atoms = list(bits(count.landmarks))
        self.landmark_atoms = np.array(atoms, dtype=np.int64)
        self.goal = _bytes_of(count.goal, state_bytes)
        self.natural = _rows((count.natural[atom] for atom in atoms), state_bytes)
        self.greedy_necessary = _rows((count.greedy_necessary[atom] for atom in atoms), state_bytes)
        self.unaccepted = np.empty(state_bytes, dtype=np.uint8)
        self.needed = np.empty(state_bytes, dtype=np.uint8)
        self.targets = np.empty(len(atoms) + 1, dtype=np.int64)

    def value(self, state_array: ByteArray, accepted: int) -> tuple[int, IntArray]:
        """h_LM of the state and the landmarks to reach next, ascending (a view of work space)."""
        from kitchen_tamp.planning.relaxed_kernel import landmark_count

        h, count = landmark_count(
            state_array, _bytes_of(accepted, self.state_bytes), self.landmark_atoms, self.goal, self.natural,
            self.greedy_necessary, self.unaccepted, self.needed, self.targets)
        return h, self.targets[:count]
