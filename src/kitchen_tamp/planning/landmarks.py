"""Fact landmarks of the delete relaxation and their orderings, found by label propagation.

A *landmark* is an atom that every plan makes true at some point (or that
holds at the start). The atoms that every *relaxed* plan makes true are found
exactly by Zhu and Givan's label propagation, the h^1 case of Keyder, Richter
and Helmert's h^m landmarks: each atom ``p`` reachable in the relaxation gets
the label

    label(p) = {p}  union  the intersection, over the actions ``a`` adding p, of
               label(a) = the union of label(q) for q in pre(a),

(atoms of the state: ``{p}``), computed as a fixpoint; the landmarks are the
labels of the goal atoms, and ``q`` in ``label(p)`` is a *natural ordering*:
``q`` holds at some time before ``p`` first does, in every plan. A relaxed
landmark is a landmark of the task, since every plan is a relaxed plan.

From the same labels come the *greedy-necessary orderings* LAMA uses to tell
when a landmark is needed again: ``q`` is greedy-necessary before ``p`` when it
is a precondition of every action that can achieve ``p`` first (an achiever
whose own label holds ``p`` cannot: it needs ``p`` already), so ``q`` must hold
right before ``p`` is first achieved.

The graph is computed once, for the initial state (as in LAMA); the landmark
count heuristic (``landmark_count``) follows which landmarks each path has
reached.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from kitchen_tamp.planning.task import bits

if TYPE_CHECKING:
    from kitchen_tamp.planning.heuristics import RelaxedExploration
    from kitchen_tamp.planning.task import State


@dataclass(frozen=True, slots=True)
class LandmarkGraph:
    """The fact landmarks of a task from one state, as bitsets over atom ids.

    ``landmarks``: the landmark atoms (goal atoms included); per atom id,
    ``natural[p]`` the landmarks ordered naturally before ``p`` and
    ``greedy_necessary[p]`` those that must hold right before ``p`` is first
    achieved (0 for atoms that are not landmarks or hold in the state).
    ``achievers[p]``: the goal-relevant actions adding ``p``.
    """

    landmarks: int
    natural: tuple[int, ...]
    greedy_necessary: tuple[int, ...]
    achievers: tuple[tuple[int, ...], ...]

    @property
    def count(self) -> int:
        return self.landmarks.bit_count()

    def orderings(self) -> int:
        """How many natural orderings the graph holds."""
        return sum(self.natural[p].bit_count() for p in bits(self.landmarks))


def atom_labels(exploration: RelaxedExploration, state: State) -> tuple[list[int], list[int]]:
    """Each atom's label and each action's label from ``state`` (-1: not reachable in the relaxation).

    A worklist fixpoint over the goal-relevant actions: an action is looked at
    again whenever the label of one of its preconditions shrinks; labels only
    shrink once set, so it ends.
    """
    n_atoms = exploration.n_atoms
    preconditions, adds, users = exploration.preconditions_of, exploration.adds_of, exploration.relevant_users
    pre_masks = exploration.pre_masks
    labels = [-1] * n_atoms
    action_labels = [-1] * len(preconditions)
    reached = state
    for atom in bits(state):
        labels[atom] = 1 << atom
    # A first-in first-out worklist without repeats (an action already waiting keeps its place).
    # Not a dict popped from the front: its deleted slots stay at the front, so finding the first
    # key costs ever more (2.1 s of 2.4 on mystery instance-10).
    waiting: set[int] = set()
    pending: deque[int] = deque()

    def wait(actions: Iterable[int]) -> None:
        for action in actions:
            if action not in waiting:
                waiting.add(action)
                pending.append(action)

    wait(exploration.relevant_free_actions)
    for atom in bits(state):
        wait(users[atom])
    while pending:
        action = pending.popleft()
        waiting.discard(action)
        if pre_masks[action] & reached != pre_masks[action]:
            continue
        label = 0
        for atom in preconditions[action]:
            label |= labels[atom]
        if label == action_labels[action]:
            continue
        action_labels[action] = label
        for atom in adds[action]:
            old = labels[atom]
            new = label | 1 << atom if old < 0 else old & (label | 1 << atom)
            if new != old:
                labels[atom] = new
                reached |= 1 << atom
                wait(users[atom])
    return labels, action_labels


def landmark_graph(exploration: RelaxedExploration, state: State) -> LandmarkGraph | None:
    """The landmarks and orderings of the task from ``state``; None if a goal is relaxed-unreachable."""
    labels, action_labels = atom_labels(exploration, state)
    landmarks = 0
    for goal in exploration.goal_ids:
        if labels[goal] < 0:
            return None
        landmarks |= labels[goal]
    natural = [0] * exploration.n_atoms
    greedy_necessary = [0] * exploration.n_atoms
    achievers = exploration.achievers
    for atom in bits(landmarks & ~state):
        natural[atom] = labels[atom] & landmarks & ~(1 << atom)
        shared = -1
        for action in achievers[atom]:
            if action_labels[action] >= 0 and not action_labels[action] >> atom & 1:
                shared &= exploration.pre_masks[action]
        greedy_necessary[atom] = shared & landmarks if shared != -1 else 0
    landmark_achievers = tuple(achievers[p] if landmarks >> p & 1 else () for p in range(exploration.n_atoms))
    return LandmarkGraph(landmarks, tuple(natural), tuple(greedy_necessary), landmark_achievers)
