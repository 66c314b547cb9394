"""The lazy alternating greedy search of ``alternating_greedy._lazy``, compiled by numba whole.

The same search, step for step: the same queues (h_FF's all and preferred
queues, the landmark count's, and the novel queue, in that order of ties),
taken in the same turns with the same boosts, each ordered by (h, first-in
first-out), the same successor order (``Task.successor_indices``), the same
evaluation (``relaxed_kernel``'s exploration, relaxed plan, landmark count and
achievers, as ``LandmarkEvaluator._evaluate_compiled`` calls them), so it
expands the states the Python search would, in the same order; only a state
costs microseconds instead of a third of a millisecond.

A state is a row of bytes (bit ``i`` of the row: atom ``i``). The states
evaluated so far are rows of one growing matrix, found again through an
open-addressing hash table of their row numbers. A queued entry is a
(parent row, action) pair: its child is computed again when it is taken out,
as Fast Downward's lazy search does. A heap key is ``h << ORDER_BITS | order``,
``order`` counting the pushes, so equal h goes first-in first-out.

This module imports numba: ``greedy_kernel_loading`` imports it only when the
same search in C (``greedy_search.c``, ``native_greedy``) is not built.
"""

from __future__ import annotations

import numba
import numpy as np
from llvmlite import ir  # type: ignore[import-untyped]
from numba.core import cgutils, types
from numba.extending import intrinsic

from kitchen_tamp.planning.relaxed_kernel import (
    UNREACHED,
    ByteArray,
    IntArray,
    _all_hold,
    _holds,
    _none_holds,
    _pop,
    _push,
    additive_exploration,
    applicable_achievers,
    landmark_count,
    supported_plan,
)
from kitchen_tamp.planning.search.greedy_kernel_loading import OUT_OF_BUDGET, SOLVED, UNSOLVABLE

ORDER_BITS = 40
"""Bits of a queue key below h: the push's number, so equal h goes first-in first-out."""

CLOCK_EVERY = 64
"""The clock is read every this many expansions (``SearchBudget.CLOCK_EVERY``'s role)."""


CLOCK_MONOTONIC = 1
"""Linux's ``clock_gettime`` clock id behind ``time.perf_counter``."""


@intrinsic
def _monotonic(typing_context):  # type: ignore[no-untyped-def]
    """``time.perf_counter()`` in compiled code: libc's ``clock_gettime(CLOCK_MONOTONIC)`` in seconds (a call
    into libc, so that the compiled search needs no Python to read the clock)."""
    def generate(context, builder, signature, arguments):  # type: ignore[no-untyped-def]
        word = ir.IntType(64)
        timespec = ir.LiteralStructType([word, word])
        function = cgutils.get_or_insert_function(  # type: ignore[no-untyped-call]
            builder.module, ir.FunctionType(ir.IntType(32), [ir.IntType(32), timespec.as_pointer()]),
            "clock_gettime")
        slot = cgutils.alloca_once(builder, timespec)  # type: ignore[no-untyped-call]
        builder.call(function, [ir.Constant(ir.IntType(32), CLOCK_MONOTONIC), slot])
        seconds = builder.sitofp(builder.load(cgutils.gep_inbounds(builder, slot, 0, 0)), ir.DoubleType())  # type: ignore[no-untyped-call]
        nanoseconds = builder.sitofp(builder.load(cgutils.gep_inbounds(builder, slot, 0, 1)), ir.DoubleType())  # type: ignore[no-untyped-call]
        return builder.fadd(seconds, builder.fmul(nanoseconds, ir.Constant(ir.DoubleType(), 1e-9)))

    return types.float64(), generate


@numba.njit(cache=True)
def _state_hash(state: ByteArray) -> np.int64:
    """FNV-1a over the state's bytes."""
    value = np.uint64(14695981039346656037)
    for byte in state:
        value = (value ^ np.uint64(byte)) * np.uint64(1099511628211)
    return np.int64(value & np.uint64(0x7FFFFFFFFFFFFFFF))


@numba.njit(cache=True)
def _find(table: IntArray, rows: ByteArray, hashes: IntArray, state: ByteArray, value: np.int64) -> np.int64:
    """The slot of ``state`` in the table, or of the empty slot where it belongs."""
    mask = len(table) - 1
    slot = value & mask
    while True:
        row = table[slot]
        if row < 0:
            return slot
        if hashes[row] == value:
            same = True
            for index in range(len(state)):
                if rows[row, index] != state[index]:
                    same = False
                    break
            if same:
                return slot
        slot = (slot + 1) & mask


@numba.njit(cache=True)
def _apply(state: ByteArray, action: int, child: ByteArray, add_start: IntArray, adds: IntArray,
           delete_start: IntArray, deletes: IntArray) -> None:
    """``child`` = the state with ``action``'s deletes cleared and its adds set (adds win)."""
    child[:] = state
    for position in range(delete_start[action], delete_start[action + 1]):
        atom = deletes[position]
        child[atom >> 3] &= np.uint8(255 - (1 << (atom & 7)))
    for position in range(add_start[action], add_start[action + 1]):
        atom = adds[position]
        child[atom >> 3] |= np.uint8(1 << (atom & 7))


@numba.njit(cache=True)
def _applicable(state: ByteArray, unconditional: IntArray, key_start: IntArray, key_actions: IntArray,
                pre_start: IntArray, pres: IntArray, neg_start: IntArray, negs: IntArray,
                out: IntArray) -> int:
    """The applicable actions in ``Task.successor_indices``'s order into ``out``; their count."""
    count = 0
    for action in unconditional:
        if _none_holds(state, negs, neg_start[action], neg_start[action + 1]):
            out[count] = action
            count += 1
    for atom in range(len(key_start) - 1):
        if key_start[atom] == key_start[atom + 1] or not _holds(state, atom):
            continue
        for position in range(key_start[atom], key_start[atom + 1]):
            action = key_actions[position]
            if _all_hold(state, pres, pre_start[action], pre_start[action + 1]) and _none_holds(
                    state, negs, neg_start[action], neg_start[action + 1]):  # as in applicable_achievers
                out[count] = action
                count += 1
    return count


@numba.njit(cache=True)
def _accept(state: ByteArray, parent_accepted: ByteArray, accepted: ByteArray, landmark_atoms: IntArray,
            natural: ByteArray, at_root: bool) -> None:
    """``LandmarkCount.accepted_after`` (``accepted_at_start`` at the root) into ``accepted``."""
    accepted[:] = parent_accepted
    for k in range(len(landmark_atoms)):
        atom = landmark_atoms[k]
        if not _holds(state, atom) or _holds(parent_accepted, atom):
            continue
        free = True
        if not at_root:
            for index in range(len(parent_accepted)):
                if natural[k, index] & (255 - parent_accepted[index]):
                    free = False
                    break
        if free:
            accepted[atom >> 3] |= np.uint8(1 << (atom & 7))


@numba.njit(cache=True)
def _evaluate(state, accepted, stamp, preferred_stamp, exploration, landmarks):  # type: ignore[no-untyped-def]
    """``LandmarkEvaluator._evaluate_compiled``: (h_FF, h_LM), (-1, -1) at a dead end; the preferred
    operators get ``preferred_stamp[action] = stamp``."""
    (n_atoms, users_start, users, adds_start, adds, precondition_counts, free_actions, goal_ids, cost,
     supporter, unsettled, settled_sum, heap, offered_atoms, level_first, level_last, next_offer, pre_start,
     pres, plan, helpful, chosen, marked, marked_atoms, stack) = exploration
    if not additive_exploration(state, n_atoms, users_start, users, adds_start, adds, precondition_counts,
                                free_actions, goal_ids, cost, supporter, unsettled, settled_sum, heap,
                                offered_atoms, level_first, level_last, next_offer):
        return -1, -1
    length, applicable = supported_plan(state, goal_ids, cost, supporter, pre_start, pres, plan, helpful,
                                        chosen, marked, marked_atoms, stack)
    for index in range(applicable):
        preferred_stamp[helpful[index]] = stamp
    (used, landmark_atoms, goal_bytes, natural, greedy_necessary, unaccepted, needed, targets,
     achievers_start, achievers, neg_start, negs, found, landmark_preferred) = landmarks
    if not used:
        return length, 0
    h_landmarks, count = landmark_count(state, accepted, landmark_atoms, goal_bytes, natural,
                                        greedy_necessary, unaccepted, needed, targets)
    if not landmark_preferred:
        return length, h_landmarks
    achieving = applicable_achievers(state, targets[:count], achievers_start, achievers, pre_start, pres,
                                     neg_start, negs, found)
    for index in range(achieving):
        preferred_stamp[found[index]] = stamp
    if achieving == 0 and count > 0:  # towards the nearest landmarks to reach next
        nearest = UNREACHED
        for index in range(count):
            nearest = min(nearest, cost[targets[index]])
        if nearest != UNREACHED:
            kept = 0
            for index in range(count):
                if cost[targets[index]] == nearest:
                    targets[kept] = targets[index]
                    kept += 1
            _, applicable = supported_plan(state, targets[:kept], cost, supporter, pre_start, pres, plan,
                                           helpful, chosen, marked, marked_atoms, stack)
            for index in range(applicable):
                preferred_stamp[helpful[index]] = stamp
    return length, h_landmarks


@numba.njit(cache=True)
def _grown_rows(rows: ByteArray, size: int) -> ByteArray:
    grown = np.zeros((size, rows.shape[1]), dtype=np.uint8)
    grown[:rows.shape[0]] = rows
    return grown


@numba.njit(cache=True)
def _grown(values: IntArray, size: int) -> IntArray:
    grown = np.empty(size, dtype=np.int64)
    grown[:len(values)] = values
    return grown


@numba.njit(cache=True)
def _rehashed(hashes: IntArray, rows: ByteArray, count: int, size: int) -> IntArray:
    table = np.full(size, -1, dtype=np.int64)
    for row in range(count):
        table[_find(table, rows, hashes, rows[row], hashes[row])] = row
    return table


@numba.njit(cache=True)
def _heap_push(heaps: IntArray, sizes: IntArray, queue: int, key: int) -> None:
    sizes[queue] = _push(heaps[queue], sizes[queue], key)


@numba.njit(cache=True)
def lazy_greedy_search(root, goal, goal_neg, successors, exploration, landmarks, settings):  # type: ignore[no-untyped-def]
    """The lazy alternating greedy search from ``root``: (outcome, goal row, expanded, generated, evaluated,
    each row's parent row, each row's action). ``settings`` is (heuristics: 1 or 2, boost, novelty,
    max_expansions or -1, deadline on ``time.perf_counter``'s clock or -1.0)."""
    unconditional, key_start, key_actions, pre_start, pres, neg_start, negs, add_start, adds, \
        delete_start, deletes = successors
    heuristics, boost, novelty, max_expansions, deadline = settings
    landmark_atoms, natural = landmarks[1], landmarks[3]
    n_bytes, n_actions = len(root), len(pre_start) - 1
    preferred_stamp = np.full(n_actions, -1, dtype=np.int64)
    applicable = np.empty(n_actions, dtype=np.int64)
    child = np.empty(n_bytes, dtype=np.uint8)
    seen = root.copy() if novelty else np.full(n_bytes, 255, dtype=np.uint8)
    capacity = 1024
    rows = np.zeros((capacity, n_bytes), dtype=np.uint8)
    accepted = np.zeros((capacity, n_bytes), dtype=np.uint8)
    parents = np.empty(capacity, dtype=np.int64)
    actions = np.empty(capacity, dtype=np.int64)
    hashes = np.empty(capacity, dtype=np.int64)
    table = np.full(2 * capacity, -1, dtype=np.int64)
    entry_capacity = 4096
    entry_parents = np.empty(entry_capacity, dtype=np.int64)
    entry_actions = np.empty(entry_capacity, dtype=np.int64)
    n_queues = 2 * heuristics + 1
    heaps = np.empty((n_queues, entry_capacity), dtype=np.int64)
    sizes = np.zeros(n_queues, dtype=np.int64)
    priorities = np.zeros(n_queues, dtype=np.int64)
    root_accepted = np.zeros(n_bytes, dtype=np.uint8)
    _accept(root, root_accepted, root_accepted, landmark_atoms, natural, True)
    best_ff, best_landmarks = _evaluate(root, root_accepted, 0, preferred_stamp, exploration, landmarks)
    entry_parents[0], entry_actions[0] = -1, -1
    _heap_push(heaps, sizes, 0, best_ff << ORDER_BITS)
    if heuristics == 2:
        _heap_push(heaps, sizes, 2, best_landmarks << ORDER_BITS)
    order, n_rows, stamp = 1, 0, 0
    expanded, generated, evaluated, check_at = 0, 1, 0, 0
    while sizes.sum() > 0:
        if expanded >= check_at:
            if ((max_expansions >= 0 and expanded >= max_expansions)
                    or (deadline >= 0.0 and _monotonic() > deadline)):  # type: ignore[call-arg]
                return OUT_OF_BUDGET, -1, expanded, generated, evaluated, parents[:n_rows], actions[:n_rows]
            check_at = expanded + CLOCK_EVERY if deadline >= 0.0 else np.iinfo(np.int64).max
            if max_expansions >= 0:
                check_at = min(check_at, max_expansions)
        side = -1
        for queue in range(n_queues):
            if sizes[queue] > 0 and (side < 0 or priorities[queue] < priorities[side]):
                side = queue
        priorities[side] += 1
        entry = heaps[side, 0] & ((1 << ORDER_BITS) - 1)
        sizes[side] = _pop(heaps[side], sizes[side])
        parent, action = entry_parents[entry], entry_actions[entry]
        if parent < 0:
            child[:] = root
        else:
            _apply(rows[parent], action, child, add_start, adds, delete_start, deletes)
        value = _state_hash(child)
        slot = _find(table, rows, hashes, child, value)
        if table[slot] >= 0:
            continue  # evaluated already
        if n_rows == capacity:
            capacity *= 2
            rows, accepted = _grown_rows(rows, capacity), _grown_rows(accepted, capacity)
            parents, actions, hashes = _grown(parents, capacity), _grown(actions, capacity), _grown(hashes,
                                                                                                   capacity)
            table = _rehashed(hashes, rows, n_rows, 2 * capacity)
            slot = _find(table, rows, hashes, child, value)
        node = n_rows
        n_rows += 1
        table[slot] = node
        rows[node] = child
        parents[node], actions[node], hashes[node] = parent, action, value
        state = rows[node]
        if parent < 0:
            accepted[node] = root_accepted
        else:
            _accept(state, accepted[parent], accepted[node], landmark_atoms, natural, False)
        stamp += 1
        h_ff, h_landmarks = _evaluate(state, accepted[node], stamp, preferred_stamp, exploration, landmarks)
        evaluated += 1
        if h_ff < 0:
            continue
        is_goal = True
        for index in range(n_bytes):
            if state[index] & goal[index] != goal[index] or state[index] & goal_neg[index]:
                is_goal = False
                break
        if is_goal:
            return SOLVED, node, expanded, generated, evaluated, parents[:n_rows], actions[:n_rows]
        improved = h_ff < best_ff or (heuristics == 2 and h_landmarks < best_landmarks)
        best_ff, best_landmarks = min(best_ff, h_ff), min(best_landmarks, h_landmarks)
        if improved:
            for queue in range(1, n_queues, 2):  # the preferred queues
                priorities[queue] -= boost
            priorities[n_queues - 1] -= boost  # the novel queue
        expanded += 1
        count = _applicable(state, unconditional, key_start, key_actions, pre_start, pres, neg_start, negs,
                            applicable)
        for index in range(count):
            action = applicable[index]
            _apply(rows[node], action, child, add_start, adds, delete_start, deletes)
            if table[_find(table, rows, hashes, child, _state_hash(child))] >= 0:
                continue
            generated += 1
            novel = False
            if novelty:
                for byte in range(n_bytes):
                    if child[byte] & (255 - seen[byte]):
                        novel = True
                        break
                if novel:
                    for byte in range(n_bytes):
                        seen[byte] |= child[byte]
            if order == entry_capacity:
                entry_capacity *= 2
                entry_parents, entry_actions = _grown(entry_parents, entry_capacity), _grown(entry_actions,
                                                                                             entry_capacity)
                grown_heaps = np.empty((n_queues, entry_capacity), dtype=np.int64)
                grown_heaps[:, :heaps.shape[1]] = heaps
                heaps = grown_heaps
            entry_parents[order], entry_actions[order] = node, action
            preferred = preferred_stamp[action] == stamp
            _heap_push(heaps, sizes, 0, h_ff << ORDER_BITS | order)
            if preferred:
                _heap_push(heaps, sizes, 1, h_ff << ORDER_BITS | order)
            if heuristics == 2:
                _heap_push(heaps, sizes, 2, h_landmarks << ORDER_BITS | order)
                if preferred:
                    _heap_push(heaps, sizes, 3, h_landmarks << ORDER_BITS | order)
            if novel:
                _heap_push(heaps, sizes, n_queues - 1, h_ff << ORDER_BITS | order)
            order += 1
    return UNSOLVABLE, -1, expanded, generated, evaluated, parents[:n_rows], actions[:n_rows]
