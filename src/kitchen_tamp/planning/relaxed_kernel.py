"""h_add's exploration and its best supporters' relaxed plan, compiled by numba over flat int arrays.

The same computation as ``RelaxedExploration.additive_costs`` and
``supported_plan`` (heuristics.py), value for value and supporter for
supporter: ``compiled_exploration.CompiledExploration`` builds the arrays once
per task and calls these kernels, and ``tests/planning/test_compiled_exploration.py``
holds the two together on many states of several IPC problems.

The Python exploration settles atoms from a list of cost buckets, each bucket
in the order its atoms were offered. Here too: each cost below
``len(level_first)`` (``compiled_exploration.BUCKET_LEVELS``) has a bucket, a
list of offers linked through their sequence numbers (``sequence`` counts the
offers) and taken first-in first-out; an offer of a higher cost goes to a
binary heap of keys ``cost << SEQUENCE_BITS | sequence``, which gives the same
order (a cost is never in both, and every bucketed cost is below every heaped
one). A stale offer (the atom got a lower cost later) is skipped as there. The
buckets take a fifth off an exploration against the heap alone (states of
pegsol, sokoban, depot and rovers; the same costs and supporters). A relevant
action keeps its count of unsettled preconditions and the sum of the settled
ones' costs apart, where Python packs both into one number (and repeats the
exploration when that overflows), so the sums are exact here with no
repetition. Like Python, the exploration finishes the cost level at which the
last goal atom is settled before it stops.

This module imports numba: only ``compiled_exploration`` imports it, and only
once a search has evaluated enough states that compiled evaluation pays for
loading it.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

IntArray = npt.NDArray[np.int64]
ByteArray = npt.NDArray[np.uint8]

UNREACHED = np.int64(1) << np.int64(62)
"""The cost of an atom not (yet) reached: above every sum of costs."""

SEQUENCE_BITS = 32
"""Bits of a heap key below the cost: the offer's sequence number, so equal costs go first-in first-out."""


@numba.njit(cache=True)
def _holds(state_bytes: ByteArray, atom: int) -> bool:
    return bool((state_bytes[atom >> 3] >> (atom & 7)) & 1 == 1)


@numba.njit(cache=True)
def _all_hold(state_bytes: ByteArray, atoms: IntArray, start: int, end: int) -> bool:
    """Whether every atom of ``atoms[start:end]`` holds in the state (a loop: numba compiles no
    generator expression into ``all``)."""
    for position in range(start, end):  # noqa: SIM110
        if not _holds(state_bytes, atoms[position]):
            return False
    return True


@numba.njit(cache=True)
def _none_holds(state_bytes: ByteArray, atoms: IntArray, start: int, end: int) -> bool:
    """Whether no atom of ``atoms[start:end]`` holds in the state."""
    for position in range(start, end):  # noqa: SIM110
        if _holds(state_bytes, atoms[position]):
            return False
    return True


@numba.njit(cache=True)
def _push(heap: IntArray, size: int, key: int) -> int:
    """Push ``key`` onto the min-heap of ``size`` keys; the new size."""
    position = size
    while position > 0:
        parent = (position - 1) >> 1
        if heap[parent] <= key:
            break
        heap[position] = heap[parent]
        position = parent
    heap[position] = key
    return size + 1


@numba.njit(cache=True)
def _pop(heap: IntArray, size: int) -> int:
    """Remove the least key of the min-heap of ``size`` keys (read it first at ``heap[0]``); the new size."""
    size -= 1
    last = heap[size]
    position = 0
    child = 1
    while child < size:
        if child + 1 < size and heap[child + 1] < heap[child]:
            child += 1
        if heap[child] >= last:
            break
        heap[position] = heap[child]
        position = child
        child = 2 * position + 1
    # Written even when the heap is now empty (``last`` back where it was): with a test around it numba
    # would count references to ``heap`` on every call.
    heap[position] = last
    return size


@numba.njit(cache=True)
def additive_exploration(state_bytes: ByteArray, n_atoms: int, users_start: IntArray, users: IntArray,
                         adds_start: IntArray, adds: IntArray, precondition_counts: IntArray,
                         free_actions: IntArray, goal_ids: IntArray, cost: IntArray, supporter: IntArray,
                         unsettled: IntArray, settled_sum: IntArray, heap: IntArray,
                         offered_atoms: IntArray, level_first: IntArray, level_last: IntArray,
                         next_offer: IntArray) -> bool:
    """Fill ``cost`` and ``supporter`` (h_add costs and best supporters) from ``state``; False if the goal is
    relaxed-unreachable. ``users`` lists each atom's relevant users (CSR by ``users_start``), ``adds``
    each action's add effects; the remaining arrays are work space of the right sizes (``level_first``
    and ``level_last``: one entry per cost kept in buckets)."""
    cost[:] = UNREACHED
    supporter[:] = -1
    unsettled[:] = precondition_counts
    settled_sum[:] = 0
    levels = len(level_first)
    # Appending to a bucket is written out at its three places: as a function of the arrays, numba
    # counts references to them on each call (see the module's callers of ``_all_hold``).
    top = -1  # the highest cost whose bucket is set up (empty or not)
    size = 0
    sequence = 0
    for atom in range(n_atoms):
        if _holds(state_bytes, atom):
            cost[atom] = 0
            offered_atoms[sequence] = atom
            next_offer[sequence] = -1
            if top < 0:
                top = 0
                level_first[0] = sequence
            else:
                next_offer[level_last[0]] = sequence
            level_last[0] = sequence
            sequence += 1
    for action in free_actions:
        for position in range(adds_start[action], adds_start[action + 1]):
            atom = adds[position]
            if cost[atom] > 1:
                cost[atom] = 1
                supporter[atom] = action
                offered_atoms[sequence] = atom
                if levels > 1:
                    while top < 1:
                        top += 1
                        level_first[top] = -1
                    next_offer[sequence] = -1
                    if level_first[1] < 0:
                        level_first[1] = sequence
                    else:
                        next_offer[level_last[1]] = sequence
                    level_last[1] = sequence
                else:
                    size = _push(heap, size, (1 << SEQUENCE_BITS) | sequence)
                sequence += 1
    level = 0
    while True:
        bucketed = level <= top
        offer = level_first[level] if bucketed else -1
        while True:
            if bucketed:
                if offer < 0:
                    break
                atom = offered_atoms[offer]
                offer = next_offer[offer]
            else:
                if size == 0 or heap[0] >> SEQUENCE_BITS != level:
                    break
                atom = offered_atoms[heap[0] & ((1 << SEQUENCE_BITS) - 1)]
                size = _pop(heap, size)
            if cost[atom] != level:
                continue  # offered again at a lower cost, and settled then
            for user_position in range(users_start[atom], users_start[atom + 1]):
                action = users[user_position]
                unsettled[action] -= 1
                settled_sum[action] += level
                if unsettled[action] == 0:
                    value = settled_sum[action] + 1
                    for position in range(adds_start[action], adds_start[action + 1]):
                        added = adds[position]
                        if value < cost[added]:
                            cost[added] = value
                            supporter[added] = action
                            offered_atoms[sequence] = added
                            if value < levels:
                                while top < value:
                                    top += 1
                                    level_first[top] = -1
                                next_offer[sequence] = -1
                                if level_first[value] < 0:
                                    level_first[value] = sequence
                                else:
                                    next_offer[level_last[value]] = sequence
                                level_last[value] = sequence
                            else:
                                size = _push(heap, size, (value << SEQUENCE_BITS) | sequence)
                            sequence += 1
        reached = True
        for goal in goal_ids:
            if cost[goal] > level:
                reached = False
                break
        if reached:
            return True
        level += 1
        while level <= top and level_first[level] < 0:
            level += 1
        if level > top:
            if size == 0:
                return False
            level = heap[0] >> SEQUENCE_BITS


@numba.njit(cache=True)
def supported_plan(state_bytes: ByteArray, targets: IntArray, cost: IntArray, supporter: IntArray,
                   pre_start: IntArray, pres: IntArray, plan: IntArray, helpful: IntArray, chosen: ByteArray,
                   marked: ByteArray, marked_atoms: IntArray, stack: IntArray) -> tuple[int, int]:
    """The best supporters' relaxed plan for ``targets`` into ``plan`` and its actions applicable in
    ``state`` into ``helpful``; returns both counts. The plan's actions come in the order
    ``RelaxedExploration.supported_plan`` gives them; ``chosen`` and ``marked`` must be all zero on entry
    and are left so."""
    depth = 0
    for target in targets:
        stack[depth] = target
        depth += 1
    length = 0
    touched = 0
    while depth > 0:
        depth -= 1
        atom = stack[depth]
        if marked[atom] or cost[atom] == 0:
            continue  # handled already, or true in the state
        marked[atom] = 1
        marked_atoms[touched] = atom
        touched += 1
        action = supporter[atom]
        if not chosen[action]:
            chosen[action] = 1
            plan[length] = action
            length += 1
            for position in range(pre_start[action], pre_start[action + 1]):
                stack[depth] = pres[position]
                depth += 1
    applicable = 0
    for index in range(length):
        action = plan[index]
        chosen[action] = 0
        if _all_hold(state_bytes, pres, pre_start[action], pre_start[action + 1]):
            helpful[applicable] = action
            applicable += 1
    for index in range(touched):
        marked[marked_atoms[index]] = 0
    return length, applicable


@numba.njit(cache=True)
def applicable_achievers(state_bytes: ByteArray, targets: IntArray, achievers_start: IntArray,
                         achievers: IntArray, pre_start: IntArray, pres: IntArray, neg_start: IntArray,
                         negs: IntArray, found: IntArray) -> int:
    """The actions achieving one of ``targets`` that are applicable in the state (their positive
    preconditions hold, their negative ones do not), into ``found``; returns their count (an action
    achieving several targets comes once per target, as ``LandmarkCount.achieving_actions`` visits it)."""
    count = 0
    for target in targets:
        for achiever_position in range(achievers_start[target], achievers_start[target + 1]):
            action = achievers[achiever_position]
            # The two tests written out here, not behind a function of both: numba then counts no
            # references to the arrays on each call (a third of the search's time on pegsol).
            if _all_hold(state_bytes, pres, pre_start[action], pre_start[action + 1]) and _none_holds(
                    state_bytes, negs, neg_start[action], neg_start[action + 1]):
                found[count] = action
                count += 1
    return count


@numba.njit(cache=True)
def landmark_count(state_bytes: ByteArray, accepted_bytes: ByteArray, landmark_atoms: IntArray,
                   goal_bytes: ByteArray, natural: ByteArray, greedy_necessary: ByteArray,
                   unaccepted_bytes: ByteArray, needed_bytes: ByteArray,
                   targets: IntArray) -> tuple[int, int]:
    """``LandmarkCount.value``: h_LM, and the landmarks to reach next into ``targets`` (ascending); returns
    h_LM and their count. Row ``k`` of ``natural`` and ``greedy_necessary`` holds the bytes of landmark
    ``landmark_atoms[k]``'s natural predecessors and greedy-necessary predecessors; the accepted landmarks
    are landmarks."""
    unaccepted_bytes[:] = 0
    needed_bytes[:] = goal_bytes
    unaccepted = 0
    for k in range(len(landmark_atoms)):
        atom = landmark_atoms[k]
        if not _holds(accepted_bytes, atom):
            unaccepted_bytes[atom >> 3] |= np.uint8(1 << (atom & 7))
            for index in range(len(needed_bytes)):
                needed_bytes[index] |= greedy_necessary[k, index]
            unaccepted += 1
    h = unaccepted
    count = 0
    for k in range(len(landmark_atoms)):
        atom = landmark_atoms[k]
        if _holds(unaccepted_bytes, atom):
            free = True
            for index in range(len(unaccepted_bytes)):
                if natural[k, index] & unaccepted_bytes[index]:
                    free = False
                    break
            if free:
                targets[count] = atom
                count += 1
        elif not _holds(state_bytes, atom) and _holds(needed_bytes, atom):
            h += 1  # accepted, false now, and needed again
            targets[count] = atom
            count += 1
    return h, count
