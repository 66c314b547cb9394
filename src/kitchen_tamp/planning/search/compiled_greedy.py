"""The lazy alternating greedy search run whole by the compiled kernel (``greedy_kernel``).

``alternating_greedy``'s lazy search hands a task over to this when the search
in C (``native_greedy``) is not built, once its evaluator has switched to the
JIT exploration (``COMPILED_AFTER_WORK``): the search then starts
again from the root in the kernel, which takes the same steps as the Python
search (the same queues, turns, ties, successor order and evaluations) and so
returns the plan the Python search would, with the same counts. The
arrays are laid out here once per task (``CompiledExploration``'s tables).
Importing this module imports numpy, not numba.
"""

from __future__ import annotations

import numpy as np

from kitchen_tamp.planning.compiled_exploration import (
    CompiledExploration,
    CompiledLandmarkCount,
    _bytes_of,
    _flat,
)
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.search.breadth_first import unsolvable_message
from kitchen_tamp.planning.search.greedy_kernel_loading import OUT_OF_BUDGET, SOLVED, GreedyKernel
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_from_rows
from kitchen_tamp.planning.task import Task, bits

SuccessorArrays = tuple[np.ndarray, ...]


def _successor_arrays(task: Task, compiled: CompiledExploration) -> SuccessorArrays:
    """Actions without positive preconditions, actions by key atom (CSR), preconditions, negative
    preconditions, adds and deletes (CSR by action), as ``greedy_kernel._applicable`` and ``_apply`` read
    them."""
    unconditional_indices, by_key = task.keyed_action_indices
    key_start, key_actions = _flat(by_key)
    delete_start, deletes = _flat(bits(action.delete) for action in task.actions)
    unconditional = np.array(unconditional_indices, dtype=np.int64)
    return (unconditional, key_start, key_actions, compiled.pre_start, compiled.pres, compiled.neg_start,
            compiled.negs, compiled.adds_start, compiled.adds, delete_start, deletes)


def _exploration_arrays(compiled: CompiledExploration) -> tuple[object, ...]:
    return (compiled.n_atoms, compiled.users_start, compiled.users, compiled.adds_start, compiled.adds,
            compiled.precondition_counts, compiled.free_actions, compiled.goal_ids, compiled.cost,
            compiled.supporter, compiled.unsettled, compiled.settled_sum, compiled.heap,
            compiled.offered_atoms, compiled.level_first, compiled.level_last, compiled.next_offer,
            compiled.pre_start, compiled.pres, compiled.plan, compiled.helpful,
            compiled.chosen, compiled.marked, compiled.marked_atoms, compiled.stack)


def _landmark_arrays(compiled: CompiledExploration, count: CompiledLandmarkCount | None,
                     landmark_preferred: bool) -> tuple[object, ...]:
    if count is None:  # the same types, empty: the kernel does not read them
        empty_rows = np.zeros((0, compiled.state_bytes), dtype=np.uint8)
        empty = np.zeros(0, dtype=np.int64)
        blank = np.zeros(compiled.state_bytes, dtype=np.uint8)
        return (False, empty, blank, empty_rows, empty_rows, blank.copy(), blank.copy(),
                np.zeros(1, np.int64), compiled.achievers_start, compiled.achievers, compiled.neg_start,
                compiled.negs, compiled.found, False)
    return (True, count.landmark_atoms, count.goal, count.natural, count.greedy_necessary, count.unaccepted,
            count.needed, count.targets, compiled.achievers_start, compiled.achievers, compiled.neg_start,
            compiled.negs, compiled.found, landmark_preferred)


def compiled_lazy_search(evaluator: LandmarkEvaluator, novelty: bool, boost: int, budget: SearchBudget,
                         kernel: GreedyKernel) -> SearchResult:
    """``alternating_greedy._lazy`` from the root, in ``kernel`` (``greedy_kernel_loading``'s)."""
    compiled, count = evaluator.compiled, evaluator.compiled_count
    if compiled is None:  # the tables without the evaluator's switch (which would import numba)
        compiled = CompiledExploration(evaluator.exploration,
                                       None if evaluator.count is None else evaluator.count.achievers)
        if evaluator.count is not None:
            count = CompiledLandmarkCount(evaluator.count, compiled.state_bytes)
    task = evaluator.exploration.task
    size = compiled.state_bytes
    settings = (2 if evaluator.count is not None else 1, boost, novelty,
                -1 if budget.max_expansions is None else budget.max_expansions,
                -1.0 if budget.deadline is None else budget.deadline)
    outcome, goal_row, expanded, generated, evaluated, parents, actions = kernel(
        _bytes_of(task.initial_state, size), _bytes_of(task.goal, size), _bytes_of(task.goal_neg, size),
        _successor_arrays(task, compiled), _exploration_arrays(compiled),
        _landmark_arrays(compiled, count, evaluator.landmark_preferred), settings)
    counts = (int(expanded), int(generated), int(evaluated))
    if outcome == SOLVED:
        plan = plan_from_rows(task, parents.tolist(), actions.tolist(), int(goal_row))
        return SearchResult("gbfs", "solved", plan, *counts, budget.elapsed())
    if outcome == OUT_OF_BUDGET:
        return SearchResult("gbfs", "budget", None, *counts, budget.elapsed(), budget.describe())
    return SearchResult("gbfs", "unsolvable", None, *counts, budget.elapsed(),
                        unsolvable_message(task, len(parents)))
