"""The lazy alternating greedy search in C (``greedy_search.c``), built at install and called through ctypes.

``alternating_greedy``'s lazy search hands a task over to a compiled search once
it has spent long enough in Python; the search then starts again from the root
and takes the Python search's steps, so the plan and the counts are the same.
numba's kernel of it (``compiled_greedy``) costs a process numpy's import (about
0.05 s of CPU) and numba's (most of a second), more than most searches take.
This is the same search written in C: ``make install``
(``python -m kitchen_tamp.cli.prepare``) compiles it with the system's C
compiler into a shared library in this package's ``__pycache__``, named after a
digest of its source and flags (an edited source is never served by a stale
library), and loading it costs ctypes' import and a ``dlopen``, a few
milliseconds. Its arrays are laid out here from the task with the standard
library's ``array``, without numpy. Without a C compiler there is no library,
and a long search hands over to numba's JIT kernel.
"""

from __future__ import annotations

import ctypes
import hashlib
from array import array
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from kitchen_tamp.planning.heuristics import BUCKET_LEVELS
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.search.breadth_first import unsolvable_message
from kitchen_tamp.planning.search.greedy_kernel_loading import OUT_OF_BUDGET, SOLVED, UNSOLVABLE
from kitchen_tamp.planning.search.partners import Partner, Turns
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult, plan_from_rows
from kitchen_tamp.planning.task import bits

SOURCE = Path(__file__).resolve().with_name("greedy_search.c")
COMPILER_FLAGS = ("-O2", "-std=c99", "-shared", "-fPIC")
"""How the library is compiled: portable optimisation, no processor-specific instructions (the search
computes with integers only)."""
OUT_OF_MEMORY = 3
"""The C search's outcome when an allocation failed."""
PORTFOLIO_MAX = 8
"""``greedy_search.c``'s PORTFOLIO_MAX: the most searches that take turns."""

_Int64s: type[ctypes._Pointer[ctypes.c_int64]] = ctypes.POINTER(ctypes.c_int64)
_Bytes: type[ctypes._Pointer[ctypes.c_uint8]] = ctypes.POINTER(ctypes.c_uint8)
_Int32s: type[ctypes._Pointer[ctypes.c_int32]] = ctypes.POINTER(ctypes.c_int32)
_Int64 = ctypes.c_int64

_TASK_FIELDS: list[tuple[str, Any]] = [
    ("n_atoms", _Int64), ("n_actions", _Int64), ("state_bytes", _Int64), ("bucket_levels", _Int64),
    ("root", _Bytes), ("goal", _Bytes), ("goal_neg", _Bytes),
    ("unconditional", _Int64s), ("n_unconditional", _Int64),
    ("key_start", _Int64s), ("key_actions", _Int64s),
    ("pre_start", _Int64s), ("pres", _Int64s), ("neg_start", _Int64s), ("negs", _Int64s),
    ("add_start", _Int32s), ("adds", _Int32s), ("delete_start", _Int64s), ("deletes", _Int64s),
    ("users_start", _Int32s), ("users", _Int32s), ("precondition_counts", _Int32s),
    ("free_actions", _Int64s), ("n_free_actions", _Int64),
    ("goal_ids", _Int64s), ("n_goal_ids", _Int64),
    ("landmarks_used", _Int64), ("landmark_preferred", _Int64),
    ("n_landmarks", _Int64), ("landmark_atoms", _Int64s),
    ("landmark_goal", _Bytes), ("natural", _Bytes), ("greedy_necessary", _Bytes),
    ("achievers_start", _Int64s), ("achievers", _Int64s),
]
"""``struct GreedyTask`` of ``greedy_search.c``, field by field."""


class _Task(ctypes.Structure):
    """``struct GreedyTask`` of ``greedy_search.c``."""

    _fields_ = _TASK_FIELDS


class _Settings(ctypes.Structure):
    """``struct GreedySettings``."""

    _fields_ = [("heuristics", _Int64), ("boost", _Int64), ("novelty", _Int64),
                ("max_expansions", _Int64), ("deadline", ctypes.c_double)]


_RESULT_FIELDS: list[tuple[str, Any]] = [
    ("outcome", _Int64), ("goal_row", _Int64), ("expanded", _Int64), ("generated", _Int64),
    ("evaluated", _Int64), ("n_rows", _Int64), ("parents", _Int64s), ("actions", _Int64s),
]
"""``struct GreedyResult``, field by field."""


class _Result(ctypes.Structure):
    """``struct GreedyResult``."""

    _fields_ = _RESULT_FIELDS


def library_path() -> Path:
    """Where the library compiled from the current source is (or would be)."""
    digest = hashlib.sha256(" ".join(COMPILER_FLAGS).encode())
    digest.update(SOURCE.read_bytes())
    return SOURCE.parent / "__pycache__" / f"native_greedy_{digest.hexdigest()[:16]}.so"


def compile_library() -> Path:
    """Compile the search into ``library_path()`` unless it is there, with ``$CC`` (else the compiler
    Python was built with, else ``cc``); libraries of earlier sources are removed. Raises ``OSError`` (no
    compiler) or ``subprocess.CalledProcessError`` (it failed)."""
    import os  # here, not at load: a search handing over imports this module
    import subprocess
    import sysconfig

    path = library_path()
    if path.exists():
        return path
    path.parent.mkdir(parents=True, exist_ok=True)
    compiler = (os.environ.get("CC") or sysconfig.get_config_var("CC") or "cc").split()
    partial = path.with_name(f"{path.stem}.{os.getpid()}.partial")
    try:
        subprocess.run([*compiler, *COMPILER_FLAGS, "-o", str(partial), str(SOURCE)], check=True,
                       capture_output=True, text=True)
        os.replace(partial, path)
    finally:
        partial.unlink(missing_ok=True)
    for stale in path.parent.glob("native_greedy_*.so"):
        if stale != path:
            stale.unlink(missing_ok=True)
    return path


def load_library() -> ctypes.CDLL | None:
    """The library compiled from the current source, or None without one."""
    path = library_path()
    if not path.exists():
        return None
    try:
        library = ctypes.CDLL(str(path))
    except OSError:
        return None
    library.greedy_portfolio.argtypes = [ctypes.POINTER(ctypes.POINTER(_Task)), ctypes.POINTER(_Settings),
                                         _Int64, _Int64, _Int64, ctypes.POINTER(_Result)]
    library.greedy_portfolio.restype = ctypes.c_int64
    library.greedy_result_free.argtypes = [ctypes.POINTER(_Result)]
    library.greedy_result_free.restype = None
    return library


class _Arrays:
    """The task's arrays, kept alive while the C search reads them."""

    def __init__(self) -> None:
        self.kept: list[array[int]] = []

    def ints(self, values: Iterable[int]) -> ctypes._Pointer[ctypes.c_int64]:
        kept = array("q", values)
        self.kept.append(kept)
        return ctypes.cast(kept.buffer_info()[0], _Int64s)

    def int32s(self, values: Iterable[int]) -> ctypes._Pointer[ctypes.c_int32]:
        kept = array("i", values)
        self.kept.append(kept)
        return ctypes.cast(kept.buffer_info()[0], _Int32s)

    def bytes(self, values: Iterable[int] | bytes) -> ctypes._Pointer[ctypes.c_uint8]:
        kept = array("B", values)
        self.kept.append(kept)
        return ctypes.cast(kept.buffer_info()[0], _Bytes)

    def csr(self, rows: Iterable[Iterable[int]]) -> tuple[ctypes._Pointer[ctypes.c_int64],
                                                          ctypes._Pointer[ctypes.c_int64]]:
        """Rows of ints as the offsets where each row starts (one more than rows) and their values."""
        starts, values = _csr(rows)
        return self.ints(starts), self.ints(values)

    def csr32(self, rows: Iterable[Iterable[int]]) -> tuple[ctypes._Pointer[ctypes.c_int32],
                                                            ctypes._Pointer[ctypes.c_int32]]:
        """``csr`` in 32-bit ints."""
        starts, values = _csr(rows)
        return self.int32s(starts), self.int32s(values)


def _csr(rows: Iterable[Iterable[int]]) -> tuple[list[int], list[int]]:
    starts = [0]
    values: list[int] = []
    for row in rows:
        values.extend(row)
        starts.append(len(values))
    return starts, values


def _task_structure(evaluator: LandmarkEvaluator, arrays: _Arrays) -> _Task:
    """The task, its relaxed exploration and its landmark count as ``struct GreedyTask``."""
    exploration, count = evaluator.exploration, evaluator.count
    task = exploration.task
    size = max(1, (exploration.n_atoms + 7) // 8)
    structure = _Task(n_atoms=exploration.n_atoms, n_actions=len(task.actions), state_bytes=size,
                      bucket_levels=BUCKET_LEVELS)
    structure.root = arrays.bytes(task.initial_state.to_bytes(size, "little"))
    structure.goal = arrays.bytes(task.goal.to_bytes(size, "little"))
    structure.goal_neg = arrays.bytes(task.goal_neg.to_bytes(size, "little"))
    unconditional, by_key = task.keyed_action_indices
    structure.unconditional, structure.n_unconditional = arrays.ints(unconditional), len(unconditional)
    structure.key_start, structure.key_actions = arrays.csr(by_key)
    structure.pre_start, structure.pres = arrays.csr(exploration.preconditions_of)
    structure.neg_start, structure.negs = arrays.csr(bits(action.pre_neg) for action in task.actions)
    structure.add_start, structure.adds = arrays.csr32(exploration.adds_of)
    structure.delete_start, structure.deletes = arrays.csr(bits(action.delete) for action in task.actions)
    structure.users_start, structure.users = arrays.csr32(exploration.relevant_users)
    structure.precondition_counts = arrays.int32s(exploration.relevant_precondition_count)
    structure.free_actions = arrays.ints(exploration.relevant_free_actions)
    structure.n_free_actions = len(exploration.relevant_free_actions)
    structure.goal_ids, structure.n_goal_ids = arrays.ints(exploration.goal_ids), len(exploration.goal_ids)
    achievers = exploration.achievers if count is None else count.achievers
    structure.achievers_start, structure.achievers = arrays.csr(achievers)
    structure.landmark_preferred = evaluator.landmark_preferred
    if count is None:
        structure.landmark_goal = structure.natural = structure.greedy_necessary = arrays.bytes(bytes(size))
        structure.landmark_atoms = arrays.ints(())
        return structure
    atoms = list(bits(count.landmarks))
    structure.landmarks_used, structure.n_landmarks = 1, len(atoms)
    structure.landmark_atoms = arrays.ints(atoms)
    structure.landmark_goal = arrays.bytes(count.goal.to_bytes(size, "little"))
    structure.natural = arrays.bytes(b"".join(count.natural[atom].to_bytes(size, "little") for atom in atoms))
    structure.greedy_necessary = arrays.bytes(
        b"".join(count.greedy_necessary[atom].to_bytes(size, "little") for atom in atoms))
    return structure


_ALL = 2**63 - 1
"""Evaluations without end: the main search alone to its end."""


def native_lazy_search(evaluator: LandmarkEvaluator, novelty: bool, boost: int, budget: SearchBudget,
                       library: ctypes.CDLL, turns: Turns | None = None) -> SearchResult:
    """``alternating_greedy._lazy`` from the root, in the C library (``load_library``'s).

    With ``turns``, the search goes alone for ``turns.alone`` evaluations; then it and the partners
    (each from its own root, on the same task) take turns of ``turns.turn`` evaluations until one
    ends: its plan, or its proof that there is none, is the answer, with the counts summed over all
    of them. A partner with landmarks needs ``evaluator`` to have the landmark graph."""
    task = evaluator.exploration.task
    arrays = _Arrays()
    structure = _task_structure(evaluator, arrays)
    deadline = -1.0 if budget.deadline is None else budget.deadline
    max_expansions = -1 if budget.max_expansions is None else budget.max_expansions
    turns = turns or Turns((), _ALL, 1)
    if len(turns.partners) >= PORTFOLIO_MAX:
        raise ValueError(f"at most {PORTFOLIO_MAX - 1} partners take turns with a search")
    main = Partner(evaluator.count is not None, evaluator.landmark_preferred, novelty)
    structures, settings = [], []
    for choices in (main, *turns.partners):
        if choices.landmarks and evaluator.count is None:
            raise ValueError("a partner with the landmark count needs an evaluator with the landmark graph")
        copy = _Task.from_buffer_copy(structure)
        copy.landmarks_used = int(choices.landmarks)
        copy.landmark_preferred = int(choices.landmarks and choices.landmark_preferred)
        structures.append(copy)
        heuristics = 2 if choices.landmarks else 1
        settings.append(_Settings(heuristics, boost, choices.novelty, max_expansions, deadline))
    tasks = (ctypes.POINTER(_Task) * len(structures))(*(ctypes.pointer(each) for each in structures))
    result = _Result()
    outcome = library.greedy_portfolio(tasks, (_Settings * len(settings))(*settings), len(structures),
                                       turns.alone, max(1, turns.turn),
                                       ctypes.byref(result))
    try:
        if outcome == OUT_OF_MEMORY:
            raise MemoryError(f"the greedy search ran out of memory after {result.expanded} expansions")
        counts = (result.expanded, result.generated, result.evaluated)
        if outcome == SOLVED:
            plan = plan_from_rows(task, result.parents, result.actions, result.goal_row)
            return SearchResult("gbfs", "solved", plan, *counts, budget.elapsed())
        if outcome == OUT_OF_BUDGET:
            return SearchResult("gbfs", "budget", None, *counts, budget.elapsed(), budget.describe())
        assert outcome == UNSOLVABLE, outcome
        return SearchResult("gbfs", "unsolvable", None, *counts, budget.elapsed(),
                            unsolvable_message(task, result.n_rows))
    finally:
        library.greedy_result_free(ctypes.byref(result))
