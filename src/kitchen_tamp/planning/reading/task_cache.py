"""Grounded tasks kept across processes, so a run on unchanged files imports neither Lark nor ``pddl``.

Parsing, checking and grounding a problem is the same work every time its
files are the same, and what a small run costs is mostly importing the parser
(Lark and the ``pddl`` package, about 50 ms on an idle machine). So
``load_task_cached`` keeps the grounded ``Task`` in
``$XDG_CACHE_HOME/kitchen_tamp/tasks`` (see ``user_cache``), in our own compact
form: ``marshal`` of plain tuples, strings and ints (bitsets are stored as atom
ids and rebuilt, since a bitset over thousands of atoms is large).

The entry's name is a SHA-256 key over everything the task depends on: the
bytes of the domain and the problem files, the cache format, our package's
version and the source of the modules that build a task, the ``pddl`` and
Lark versions and the Python version. The key is also the entry's first
field, so a renamed or stale entry is a miss. Any entry that cannot be read
or decoded (truncated, corrupt, another format) is a miss too: the task is
loaded with ``loading.load_task`` and the entry written again, atomically
(``atomic_files``). Only a task that loaded without error is stored, so a bad
file gets ``load_task``'s own error message every time. A cache directory that
cannot be written only means parsing every run. At most ``MAX_ENTRIES``
entries are kept (the least recently used go first), each at most
``MAX_ENTRY_BYTES``.
"""

from __future__ import annotations

import contextlib
import marshal
import os
import sys
from collections.abc import Iterable
from hashlib import sha256
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import kitchen_tamp
from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.planning.loading import default_domain, load_task
from kitchen_tamp.planning.task import GroundAction, Task, bits
from kitchen_tamp.user_cache import cache_directory

CACHE_FORMAT = 1
"""Bumped when the layout of an entry changes."""

MAX_ENTRIES = 32
"""Entries kept; storing one more removes the least recently used."""

MAX_ENTRY_BYTES = 16 * 1024 * 1024
"""A task whose entry would be larger is not stored (it is loaded from its files every run)."""

TASK_SOURCES = ("errors.py", "grounding.py", "loading.py", "schemas.py", "task.py",
                "reading/package_reader.py", "reading/source.py", "reading/syntax.py",
                "reading/pddl_text.py", "reading/strips_text_reader.py", "reading/task_cache.py")
"""Our modules whose code decides what a loaded task is; editing one makes every entry stale."""

ENTRY_SUFFIX = ".task"
ENTRY_FOLDER = "tasks"
"""The entries' folder, in the user's cache directory."""


def task_cache_directory() -> Path:
    """Where the entries live (raises ``RuntimeError`` without a home directory, as ``cache_directory``)."""
    return cache_directory() / ENTRY_FOLDER


def load_task_cached(problem_path: str | Path, domain_path: str | Path | None = None) -> Task:
    """``load_task(problem_path, domain_path)``, served from the cache when the files are unchanged."""
    problem = Path(problem_path)
    domain = Path(domain_path) if domain_path is not None else default_domain(problem)
    try:
        key = task_key(domain.read_bytes(), problem.read_bytes())
        entry: Path | None = task_cache_directory() / (key + ENTRY_SUFFIX)
    except (OSError, RuntimeError):  # unreadable files (load_task says why) or no home: no cache
        entry = None
    if entry is not None:
        task = _read_entry(entry, key)
        if task is not None:
            return task
    task = load_task(problem, domain)
    if entry is not None:
        _write_entry(entry, key, task)
    return task


def task_key(domain: bytes, problem: bytes) -> str:
    """The hex SHA-256 naming the entry for these file contents under this code and these versions."""
    digest = sha256()
    for part in (str(CACHE_FORMAT).encode(), kitchen_tamp.__version__.encode(), sys.version.encode(),
                 sys.implementation.cache_tag.encode(), _versions_digest(),
                 sha256(domain).digest(), sha256(problem).digest()):
        digest.update(len(part).to_bytes(8, "little"))
        digest.update(part)
    return digest.hexdigest()


def _versions_digest() -> bytes:
    """SHA-256 of our task-building sources and of the files that carry the pddl and Lark versions."""
    digest = sha256()
    planning = Path(__file__).parent.parent
    files = [planning / name for name in TASK_SOURCES]
    for package, version_file in (("pddl", "__version__.py"), ("lark", "__init__.py")):
        spec = find_spec(package)
        locations = list(spec.submodule_search_locations or []) if spec is not None else []
        files.extend(Path(location, version_file) for location in locations[:1])
    for file in files:
        try:
            digest.update(file.read_bytes())
        except OSError:
            digest.update(b"missing " + os.fsencode(file))
    return digest.digest()


def encode_task(task: Task) -> tuple[Any, ...]:
    """The task as plain tuples, strings and ints (bitsets as sorted atom ids)."""
    actions = tuple((a.name, a.args, a.pre_ids, tuple(bits(a.pre_neg)), a.add_ids, tuple(bits(a.delete)))
                    for a in task.actions)
    return (task.name, task.domain_name, tuple(task.objects.items()), task.init_atoms, task.goal_atoms,
            task.negative_goal_atoms, task.atoms, tuple(bits(task.initial_state)), tuple(bits(task.goal)),
            tuple(bits(task.goal_neg)), actions, task.unreachable_goal_atoms)


def decode_task(fields: tuple[Any, ...]) -> Task:
    """The ``Task`` that ``encode_task`` encoded."""
    (name, domain_name, objects, init_atoms, goal_atoms, negative_goal_atoms, atoms, initial_state, goal,
     goal_neg, actions, unreachable) = fields
    bit = [1 << i for i in range(len(atoms))]

    def mask(ids: Iterable[int]) -> int:
        value = 0
        for i in ids:
            value |= bit[i]
        return value

    return Task(
        name=name, domain_name=domain_name, objects=dict(objects), init_atoms=init_atoms,
        goal_atoms=goal_atoms, negative_goal_atoms=negative_goal_atoms,
        atoms=atoms, initial_state=mask(initial_state),
        goal=mask(goal), goal_neg=mask(goal_neg),
        actions=tuple(GroundAction(action_name, args, mask(pre_ids), mask(pre_neg), mask(add_ids),
                                             mask(delete), pre_ids, add_ids)
                      for action_name, args, pre_ids, pre_neg, add_ids, delete in actions),
        unreachable_goal_atoms=unreachable)


def _read_entry(entry: Path, key: str) -> Task | None:
    try:
        stored_key, fields = marshal.loads(entry.read_bytes())
        if stored_key != key:
            return None
        task = decode_task(fields)
    except Exception:  # missing, unreadable, truncated, corrupt or another layout: a miss
        return None
    with contextlib.suppress(OSError):  # recently used; a read-only directory just keeps the old time
        os.utime(entry)
    return task


def _write_entry(entry: Path, key: str, task: Task) -> None:
    data = marshal.dumps((key, encode_task(task)))
    if len(data) > MAX_ENTRY_BYTES:
        return
    with contextlib.suppress(OSError):  # an unwritable cache directory costs time next run, nothing else
        write_atomically(entry, data)
        _evict(entry.parent)


def _evict(directory: Path) -> None:
    """Remove the least recently used entries beyond ``MAX_ENTRIES``."""
    entries = []
    for path in directory.glob("*" + ENTRY_SUFFIX):
        with contextlib.suppress(OSError):  # another process may have removed it meanwhile
            entries.append((path.stat().st_mtime_ns, path.name, path))
    entries.sort()
    for _, _, path in entries[:max(0, len(entries) - MAX_ENTRIES)]:
        with contextlib.suppress(OSError):
            path.unlink()
