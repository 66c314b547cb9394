"""The task cache: built cold, served warm without Lark or pddl, rebuilt when corrupt, stale or changed."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from kitchen_tamp.planning import PlanningInputError, Task, load_task
from kitchen_tamp.planning.reading import task_cache
from kitchen_tamp.planning.reading.task_cache import ENTRY_SUFFIX, load_task_cached, task_cache_directory
from tests.planning.conftest import DATA, KITCHEN, REPO, SMALL_TASKS


@pytest.fixture
def loads(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[Path]:
    """An empty cache under ``tmp_path``; records each problem that had to be loaded from its files."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    loaded: list[Path] = []
    original = task_cache.load_task

    def counting_load(problem: str | Path, domain: str | Path | None = None) -> Task:
        loaded.append(Path(problem))
        return original(problem, domain)

    monkeypatch.setattr(task_cache, "load_task", counting_load)
    return loaded


def entries() -> list[Path]:
    return sorted(task_cache_directory().glob("*" + ENTRY_SUFFIX))


def same_task(a: Task, b: Task) -> bool:
    """Equal as the searches see them: every field, and each action's id tuples too."""
    return a == b and all(x.pre_ids == y.pre_ids and x.add_ids == y.add_ids
                          for x, y in zip(a.actions, b.actions, strict=True))


@pytest.mark.parametrize("name", sorted(SMALL_TASKS))
def test_a_cold_load_stores_the_task_and_a_warm_one_reads_the_same_task(loads: list[Path], name: str) -> None:
    problem, domain = SMALL_TASKS[name]
    cold = load_task_cached(problem, domain)
    assert loads == [problem] and len(entries()) == 1
    warm = load_task_cached(problem, domain)
    assert loads == [problem]  # served from the entry
    assert same_task(warm, cold) and same_task(warm, load_task(problem, domain))


def test_corrupt_and_stale_entries_are_rebuilt(loads: list[Path]) -> None:
    problem = KITCHEN / "problem_hard.pddl"
    expected = load_task_cached(problem)
    (entry,) = entries()
    good = entry.read_bytes()
    for damaged in (b"", b"not marshal at all", good[: len(good) // 2]):
        entry.write_bytes(damaged)
        assert same_task(load_task_cached(problem), expected)
        assert entry.read_bytes() == good  # written again
    # A whole entry under another task's name (another key inside) is stale, not served.
    other = KITCHEN / "problem.pddl"
    load_task_cached(other)
    (other_entry,) = (e for e in entries() if e != entry)
    entry.write_bytes(other_entry.read_bytes())
    assert same_task(load_task_cached(problem), expected)
    assert len(loads) == 6


def test_a_changed_file_is_loaded_again(loads: list[Path], tmp_path: Path) -> None:
    problem = tmp_path / "problem.pddl"
    text = (KITCHEN / "problem.pddl").read_text()
    problem.write_text(text)
    domain = KITCHEN / "domain.pddl"
    first = load_task_cached(problem, domain)
    problem.write_text(text.replace("(boxOn sugar countertop)", "(boxOn sugar stove)", 1))
    changed = load_task_cached(problem, domain)
    assert len(loads) == 2 and changed.goal_atoms != first.goal_atoms
    assert same_task(changed, load_task(problem, domain))


def test_a_bad_file_is_never_cached_and_keeps_its_message(loads: list[Path], tmp_path: Path) -> None:
    problem = tmp_path / "problem.pddl"
    problem.write_text((KITCHEN / "problem.pddl").read_text().replace("(:init", "(:init (boxOn tea stove)"))
    with pytest.raises(PlanningInputError) as expected:
        load_task(problem, KITCHEN / "domain.pddl")
    for _ in range(2):
        with pytest.raises(PlanningInputError) as cached:
            load_task_cached(problem, KITCHEN / "domain.pddl")
        assert str(cached.value) == str(expected.value)
    with pytest.raises(PlanningInputError, match="problem file not found"):
        load_task_cached(tmp_path / "missing.pddl", KITCHEN / "domain.pddl")
    assert not entries()


def test_an_unwritable_cache_directory_still_loads(loads: list[Path]) -> None:
    task_cache_directory().parent.mkdir(parents=True)
    task_cache_directory().write_text("a file where the cache directory should be")
    problem = KITCHEN / "problem.pddl"
    assert same_task(load_task_cached(problem), load_task_cached(problem))
    assert len(loads) == 2  # nothing cached, nothing failed


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories; "
                    "the file-in-the-way test covers an unwritable cache")
def test_a_read_only_cache_directory_still_loads(loads: list[Path]) -> None:
    problem = KITCHEN / "problem.pddl"
    load_task_cached(problem)
    task_cache_directory().chmod(0o500)
    try:
        load_task_cached(problem)  # a hit cannot refresh its time: harmless
        load_task_cached(DATA / "blocks_sussman.pddl", DATA / "blocks_domain.pddl")
        assert len(loads) == 2 and len(entries()) == 1
    finally:
        task_cache_directory().chmod(0o700)


def test_only_the_most_recently_used_entries_are_kept(
        loads: list[Path], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(task_cache, "MAX_ENTRIES", 2)
    kitchen, hard, sussman = (SMALL_TASKS[name] for name in ("kitchen", "kitchen_hard", "sussman"))
    load_task_cached(*kitchen)
    load_task_cached(*hard)
    os.utime(entries()[0], (1, 1))
    os.utime(entries()[1], (1, 1))
    load_task_cached(*kitchen)  # a hit: kitchen is now the most recently used
    load_task_cached(*sussman)
    assert len(entries()) == 2
    load_task_cached(*kitchen)
    load_task_cached(*sussman)
    assert [p.name for p in loads] == ["problem.pddl", "problem_hard.pddl", "blocks_sussman.pddl"]


def test_cold_and_warm_runs_of_the_planner_import_neither_lark_nor_pddl(tmp_path: Path) -> None:
    """The first run reads the kitchen with the fast reader and stores the task; the second
    loads it from the task cache; neither needs the pddl package."""
    probe = (
        "import sys\n"
        "from kitchen_tamp.cli.activity_planning import main\n"
        "code = main(['problem_hard.pddl', '--planner', 'gbfs'])\n"
        "parser = sorted(m for m in sys.modules if m.split('.')[0] in {'lark', 'pddl'})\n"
        "print('parser modules:', parser[:3])\n"
        "sys.exit(code)\n")
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}
    tasks = tmp_path / "cache" / "kitchen_tamp" / "tasks"
    stored = []
    for _ in range(2):
        run = subprocess.run([sys.executable, "-c", probe], cwd=REPO, capture_output=True, text=True, env=env)
        assert run.returncode == 0, run.stderr
        assert "7. placeOn spam stove" in run.stdout
        assert "parser modules: []" in run.stdout
        stored.append(sorted(p.name for p in tasks.iterdir()))
    assert len(stored[0]) == 1  # the cold run read the files and stored the task
    assert stored[1] == stored[0]  # the warm run found it
