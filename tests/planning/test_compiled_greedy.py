"""The compiled lazy greedy search takes the Python search's steps: the same plan after the same counts.

The Python search hands over to a compiled search (the search in C, or numba's JIT kernel) from the
first state, after some Python work, or never: ``gbfs`` returns the same plan after the same expansions,
generations and evaluations, and the plan is valid.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from kitchen_tamp.planning import landmark_count as landmark_count_module
from kitchen_tamp.planning import load_task
from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.search import alternating_greedy
from kitchen_tamp.planning.search import greedy_kernel_loading as loading
from kitchen_tamp.planning.search.alternating_greedy import alternating_greedy_search
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult
from kitchen_tamp.planning.task import Task
from kitchen_tamp.planning.validation import validate_plan
from tests.planning.conftest import REPO, data_task

IPC = REPO / "benchmarks" / "ipc"


def _load(domain: str, problem: str) -> Task:
    return load_task(IPC / domain / problem, IPC / domain / "domain.pddl")


NO_C_SEARCH = "no C search built for this source (make install, with a C compiler)"


@pytest.fixture(params=["C", "jit"])
def kernel(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> str:
    """Each test runs with the search in C (built by ``make install``) and with numba's JIT kernel."""
    if request.param == "C":
        if loading.native_library() is None:
            pytest.skip(NO_C_SEARCH)
    else:
        monkeypatch.setattr(loading, "native_library", lambda: None)
    return str(request.param)


def _search(task: Task, after_work: int, monkeypatch: pytest.MonkeyPatch, expansions: int = 20_000,
            **options: bool) -> SearchResult:
    """gbfs with the evaluator's switch after ``after_work`` (never: 10**18), which hands the search over
    (the hand-over by CPU time is off)."""
    monkeypatch.setattr(landmark_count_module, "COMPILED_AFTER_WORK", after_work)
    monkeypatch.setattr(loading, "NATIVE_HANDOVER_AFTER_SECONDS", INFINITY)
    return alternating_greedy_search(task, SearchBudget(None, expansions), **options)


def _counts(result: SearchResult) -> tuple[object, ...]:
    return result.status, result.plan, result.expanded, result.generated, result.evaluated


@pytest.mark.parametrize(("domain", "problem"), [("sokoban", "task23.pddl"), ("pegsol", "task13.pddl"),
                                                 ("rovers", "task08.pddl"), ("mystery", "instance-6.pddl"),
                                                 ("satellite", "task08.pddl")])
def test_the_kernel_takes_the_python_searchs_steps(domain: str, problem: str, kernel: str,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load(domain, problem)
    python = _search(task, 10**18, monkeypatch)
    compiled = _search(task, -1, monkeypatch)
    assert python.solved and python.plan is not None
    assert _counts(compiled) == _counts(python)
    assert validate_plan(task, python.plan).valid


def test_the_hand_over_in_mid_search_gives_the_same_search(kernel: str,
                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load("depot", "task13.pddl")
    python = _search(task, 10**18, monkeypatch)
    from kitchen_tamp.planning.heuristics import RelaxedExploration
    from kitchen_tamp.planning.landmark_count import LandmarkEvaluator

    work = LandmarkEvaluator(RelaxedExploration(task, "hadd")).work_per_evaluation
    handed_over = _search(task, 20 * work, monkeypatch)  # after 20 evaluations in Python
    assert python.evaluated > 20
    assert _counts(handed_over) == _counts(python)


@pytest.mark.parametrize("options", [{"landmarks": False}, {"novelty": False}, {"landmark_preferred": False}])
def test_the_kernel_follows_the_options(options: dict[str, bool], kernel: str,
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load("sokoban", "task01.pddl")
    python = _search(task, 10**18, monkeypatch, **options)
    assert python.solved
    assert _counts(_search(task, -1, monkeypatch, **options)) == _counts(python)


def test_the_kernel_stops_at_the_expansion_budget(kernel: str, monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load("sokoban", "task23.pddl")
    python = _search(task, 10**18, monkeypatch, expansions=300)
    compiled = _search(task, -1, monkeypatch, expansions=300)
    assert compiled.status == python.status == "budget"
    assert compiled.expanded == python.expanded == 300
    assert (compiled.generated, compiled.evaluated) == (python.generated, python.evaluated)


def test_the_kernel_proves_a_task_unsolvable_as_python_does(kernel: str,
                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    task = data_task("delivery_unsolvable.pddl", "delivery_domain.pddl")
    python = _search(task, 10**18, monkeypatch)
    compiled = _search(task, -1, monkeypatch)
    assert python.status == "unsolvable" and python.expanded > 0
    assert _counts(compiled) == _counts(python)
    assert compiled.message == python.message


def _imported_by_gbfs(module: str, domain: str, problem: str, before_search: str = "") -> bool:
    code = ("import sys\n"
            "from kitchen_tamp.planning import load_task, plan\n"
            "from kitchen_tamp.planning.search import greedy_kernel_loading as loading\n"
            f"task = load_task({str(IPC / domain / problem)!r}, {str(IPC / domain / 'domain.pddl')!r})\n"
            f"{before_search}"
            "assert plan(task, 'gbfs').solved\n"
            f"print({module!r} in sys.modules)\n")
    output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return output.stdout.strip() == "True"


def test_a_small_task_does_not_import_numba() -> None:
    assert not _imported_by_gbfs("numba", "sokoban", "task01.pddl")


def test_with_the_c_search_a_large_search_imports_neither_numpy_nor_numba() -> None:
    if loading.native_library() is None:
        pytest.skip(NO_C_SEARCH)
    assert not _imported_by_gbfs("numpy", "sokoban", "task23.pddl")
    assert not _imported_by_gbfs("numba", "sokoban", "task23.pddl")


def test_a_search_hands_over_before_its_evaluation_would_import_numba() -> None:
    if loading.native_library() is None:
        pytest.skip(NO_C_SEARCH)
    # the evaluator's work would take it to the compiled exploration at its fourth state, the clock never
    before = ("import kitchen_tamp.planning.landmark_count as counting\n"
              "from kitchen_tamp.planning.heuristics import RelaxedExploration\n"
              "work = counting.LandmarkEvaluator(RelaxedExploration(task, 'hadd')).work_per_evaluation\n"
              "counting.COMPILED_AFTER_WORK = 3 * work\n"
              "loading.NATIVE_HANDOVER_AFTER_SECONDS = 1e9\n")
    assert not _imported_by_gbfs("numba", "sokoban", "task23.pddl", before)


def test_a_search_whose_root_is_dear_hands_over_after_it(monkeypatch: pytest.MonkeyPatch) -> None:
    if loading.native_library() is None:
        pytest.skip(NO_C_SEARCH)
    task = _load("sokoban", "task23.pddl")
    python = _search(task, 10**18, monkeypatch)
    evaluated: list[object] = []
    evaluate = landmark_count_module.LandmarkEvaluator.evaluate

    def counted(self: landmark_count_module.LandmarkEvaluator, *args: object) -> object:
        evaluated.append(args)
        return evaluate(self, *args)  # type: ignore[arg-type]

    monkeypatch.setattr(landmark_count_module.LandmarkEvaluator, "evaluate", counted)
    monkeypatch.setattr(alternating_greedy._Handover, "root_evaluated",
                        lambda self, h_ff, seconds: setattr(self, "due_at", 0.0))  # any root is dear
    assert _counts(alternating_greedy_search(task, SearchBudget(None, 20_000))) == _counts(python)
    assert len(evaluated) == 2  # the root, in Python, twice; then every state in C


def test_a_root_is_dear_when_its_h_ff_evaluations_cost_more_than_handing_over(
        monkeypatch: pytest.MonkeyPatch) -> None:
    clock = [10.0]
    monkeypatch.setattr(alternating_greedy.time, "process_time", lambda: clock[0])
    monkeypatch.setattr(loading, "NATIVE_HANDOVER_AFTER_SECONDS", 0.005)
    evaluator = LandmarkEvaluator(RelaxedExploration(_load("pegsol", "task13.pddl"), "hadd"))
    handover = alternating_greedy._Handover(evaluator, True, 1000, SearchBudget(None, None))
    handover.root_evaluated(20.0, 0.0002)  # 4 ms of evaluations at the least
    assert not handover.due()
    handover.root_evaluated(30.0, 0.0002)  # 6 ms
    assert handover.due()


def test_without_the_c_search_its_clock_leaves_the_search_in_python(monkeypatch: pytest.MonkeyPatch) -> None:
    clock = [10.0]
    monkeypatch.setattr(alternating_greedy.time, "process_time", lambda: clock[0])
    monkeypatch.setattr(loading, "NATIVE_HANDOVER_AFTER_SECONDS", 0.005)
    monkeypatch.setattr(loading, "native_library", lambda: None)
    evaluator = LandmarkEvaluator(RelaxedExploration(_load("pegsol", "task13.pddl"), "hadd"))
    handover = alternating_greedy._Handover(evaluator, True, 1000, SearchBudget(None, None))
    assert not handover.due()
    clock[0] += 0.006
    assert handover.due()  # the C search's turn
    assert handover.search() is None  # none built: numba's kernel waits for the evaluator's switch
    assert handover.native_looked_for and not handover.due()


def test_the_c_search_is_looked_for_on_its_own_clock(monkeypatch: pytest.MonkeyPatch) -> None:
    if loading.native_library() is None:
        pytest.skip(NO_C_SEARCH)
    task = _load("pegsol", "task13.pddl")
    python = _search(task, 10**18, monkeypatch)
    monkeypatch.setattr(loading, "NATIVE_HANDOVER_AFTER_SECONDS", 0.0)  # at the first state after the root
    handed_over = alternating_greedy_search(task, SearchBudget(None, 20_000))
    assert _counts(handed_over) == _counts(python)
