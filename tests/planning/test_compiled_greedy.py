"""The compiled lazy greedy search takes the Python search's steps: the same plan after the same counts.

The Python search hands over to the kernel once its evaluator switches to the compiled exploration;
from the first state (``COMPILED_AFTER_WORK`` -1), after some Python work, or never, ``gbfs`` returns
the same plan after the same expansions, generations and evaluations, and the plan is valid.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from kitchen_tamp.planning import landmark_count as landmark_count_module
from kitchen_tamp.planning import load_task
from kitchen_tamp.planning.search.alternating_greedy import alternating_greedy_search
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult
from kitchen_tamp.planning.task import Task
from kitchen_tamp.planning.validation import validate_plan
from tests.planning.conftest import REPO

IPC = REPO / "benchmarks" / "ipc"


def _load(domain: str, problem: str) -> Task:
    return load_task(IPC / domain / problem, IPC / domain / "domain.pddl")


def _search(task: Task, after_work: int, monkeypatch: pytest.MonkeyPatch, expansions: int = 20_000,
            **options: bool) -> SearchResult:
    monkeypatch.setattr(landmark_count_module, "COMPILED_AFTER_WORK", after_work)
    return alternating_greedy_search(task, SearchBudget(None, expansions), **options)


def _counts(result: SearchResult) -> tuple[object, ...]:
    return result.status, result.plan, result.expanded, result.generated, result.evaluated


@pytest.mark.parametrize(("domain", "problem"), [("sokoban", "task23.pddl"), ("pegsol", "task13.pddl"),
                                                 ("rovers", "task08.pddl"), ("mystery", "instance-6.pddl"),
                                                 ("satellite", "task08.pddl")])
def test_the_kernel_takes_the_python_searchs_steps(domain: str, problem: str,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load(domain, problem)
    python = _search(task, 10**18, monkeypatch)
    compiled = _search(task, -1, monkeypatch)
    assert python.solved and python.plan is not None
    assert _counts(compiled) == _counts(python)
    assert validate_plan(task, python.plan).valid


def test_the_hand_over_in_mid_search_gives_the_same_search(monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load("depot", "task13.pddl")
    python = _search(task, 10**18, monkeypatch)
    from kitchen_tamp.planning.heuristics import RelaxedExploration
    from kitchen_tamp.planning.landmark_count import LandmarkEvaluator

    work = LandmarkEvaluator(RelaxedExploration(task, "hadd")).work_per_evaluation
    handed_over = _search(task, 20 * work, monkeypatch)  # after 20 evaluations in Python
    assert python.evaluated > 20
    assert _counts(handed_over) == _counts(python)


@pytest.mark.parametrize("options", [{"landmarks": False}, {"novelty": False}])
def test_the_kernel_follows_the_options(options: dict[str, bool], monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load("sokoban", "task01.pddl")
    python = _search(task, 10**18, monkeypatch, **options)
    assert python.solved
    assert _counts(_search(task, -1, monkeypatch, **options)) == _counts(python)


def test_the_kernel_stops_at_the_expansion_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load("sokoban", "task23.pddl")
    python = _search(task, 10**18, monkeypatch, expansions=300)
    compiled = _search(task, -1, monkeypatch, expansions=300)
    assert compiled.status == python.status == "budget"
    assert compiled.expanded == python.expanded == 300
    assert (compiled.generated, compiled.evaluated) == (python.generated, python.evaluated)


def test_a_small_task_does_not_import_numba() -> None:
    code = ("import sys\n"
            "from kitchen_tamp.planning import load_task, plan\n"
            f"task = load_task({str(IPC / 'sokoban' / 'task01.pddl')!r}, "
            f"{str(IPC / 'sokoban' / 'domain.pddl')!r})\n"
            "assert plan(task, 'gbfs').solved\n"
            "print('numba' in sys.modules)\n")
    output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert output.stdout.strip() == "False"
