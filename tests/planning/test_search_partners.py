"""Searches taking turns (``partners``): the first to end answers as the Python search with its choices would.

``greedy_portfolio`` (``greedy_search.c``) runs the main search alone for a number of evaluations, then
it and its partners in turns of a number of evaluations. Each search's steps are its own, so which one
ends first, and after how many evaluations of each, follows from how many evaluations each needs alone
(the Python search's counts): the answer is that search's plan, and the counts are the sums.
"""

from __future__ import annotations

import pytest

from kitchen_tamp.planning import landmark_count as landmark_count_module
from kitchen_tamp.planning.heuristics import INFINITY, RelaxedExploration
from kitchen_tamp.planning.landmark_count import LandmarkEvaluator
from kitchen_tamp.planning.search import greedy_kernel_loading as loading
from kitchen_tamp.planning.search import partners as partners_module
from kitchen_tamp.planning.search.alternating_greedy import alternating_greedy_search
from kitchen_tamp.planning.search.native_greedy import native_lazy_search
from kitchen_tamp.planning.search.partners import PARTNERS, Partner, Turns
from kitchen_tamp.planning.search.result import SearchBudget, SearchResult
from kitchen_tamp.planning.task import Task
from kitchen_tamp.planning.validation import validate_plan
from tests.planning.conftest import REPO, data_task
from tests.planning.test_compiled_greedy import NO_C_SEARCH

IPC = REPO / "benchmarks" / "ipc"

H_FF_ALONE, LANDMARKS_WITHOUT_NOVELTY = PARTNERS


@pytest.fixture
def library() -> object:
    library = loading.native_library()
    if library is None:
        pytest.skip(NO_C_SEARCH)
    return library


def _load(domain: str, problem: str) -> Task:
    from kitchen_tamp.planning import load_task

    return load_task(IPC / domain / problem, IPC / domain / "domain.pddl")


def _python(task: Task, monkeypatch: pytest.MonkeyPatch, choices: Partner | None = None) -> SearchResult:
    """The search in Python alone from start to end (no hand-over), with the main choices or a partner's."""
    monkeypatch.setattr(landmark_count_module, "COMPILED_AFTER_WORK", 10**18)
    monkeypatch.setattr(loading, "NATIVE_HANDOVER_AFTER_SECONDS", INFINITY)
    if choices is None:
        return alternating_greedy_search(task, SearchBudget(None, None))
    return alternating_greedy_search(task, SearchBudget(None, None), landmarks=choices.landmarks,
                                     landmark_preferred=choices.landmark_preferred, novelty=choices.novelty)


def _turns(needed: list[int], alone: int, turn: int) -> tuple[int, list[int]]:
    """Which search ends first and how many evaluations each has made then, in greedy_portfolio's turns."""
    done = [0] * len(needed)
    done[0] = min(needed[0], alone)
    if done[0] == needed[0]:
        return 0, done
    while True:
        for k, need in enumerate(needed):
            done[k] = min(need, done[k] + turn)
            if done[k] == need:
                return k, done


def _portfolio(task: Task, library: object, partners: tuple[Partner, ...], alone: int, turn: int,
               expansions: int | None = None) -> SearchResult:
    evaluator = LandmarkEvaluator(RelaxedExploration(task, "hadd"))
    return native_lazy_search(evaluator, True, 1000, SearchBudget(None, expansions), library,  # type: ignore[arg-type]
                              Turns(partners, alone, turn))


@pytest.mark.parametrize(("domain", "problem", "alone", "turn"), [
    ("pegsol", "task23.pddl", 100, 50),      # the landmark count without novelty needs a sixth of the main's
    ("scanalyzer", "task13.pddl", 40, 7),    # both partners need a third of the main's
    ("woodworking", "task05.pddl", 10, 3),   # h_FF alone needs a hundred times the main's
    ("pegsol", "task23.pddl", 10**6, 50),    # the main search ends alone
])
def test_the_first_search_to_end_answers_with_its_own_plan(domain: str, problem: str, alone: int, turn: int,
                                                           library: object,
                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    task = _load(domain, problem)
    alone_runs = [_python(task, monkeypatch), *(_python(task, monkeypatch, choices) for choices in PARTNERS)]
    assert all(run.solved for run in alone_runs)
    winner, evaluations = _turns([run.evaluated for run in alone_runs], alone, turn)
    together = _portfolio(task, library, PARTNERS, alone, turn)
    assert together.solved and together.plan == alone_runs[winner].plan
    assert together.evaluated == sum(evaluations)
    assert together.expanded >= alone_runs[winner].expanded
    assert together.plan is not None and validate_plan(task, together.plan).valid


def test_turns_are_counted_so_the_same_task_gets_the_same_answer(library: object) -> None:
    task = _load("pegsol", "task23.pddl")
    first, second = (_portfolio(task, library, PARTNERS, 50, 20) for _ in range(2))
    assert (first.plan, first.expanded, first.generated, first.evaluated) == (
        second.plan, second.expanded, second.generated, second.evaluated)


def test_any_search_running_out_of_states_proves_the_task_unsolvable(library: object,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    task = data_task("delivery_unsolvable.pddl", "delivery_domain.pddl")
    alone = _python(task, monkeypatch)
    together = _portfolio(task, library, PARTNERS, 5, 3)
    assert alone.status == together.status == "unsolvable"
    assert together.message == alone.message


def test_the_expansion_budget_is_shared_by_the_searches(library: object) -> None:
    task = _load("pegsol", "task23.pddl")  # the main search and h_FF alone need over 1,000 expansions each
    together = _portfolio(task, library, (H_FF_ALONE,), 1, 1, expansions=300)
    assert together.status == "budget"
    assert together.expanded == 300


def test_a_gbfs_search_takes_its_partners_after_the_work_set(library: object,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    """Through ``alternating_greedy_search``: the partners join once the main search has evaluated
    ``PARTNERS_AFTER_WORK`` divided by the evaluator's work per evaluation."""
    task = _load("pegsol", "task23.pddl")
    alone_runs = [_python(task, monkeypatch), *(_python(task, monkeypatch, choices) for choices in PARTNERS)]
    monkeypatch.setattr(loading, "NATIVE_HANDOVER_AFTER_SECONDS", 0.0)  # to C at once
    work = LandmarkEvaluator(RelaxedExploration(task, "hadd")).work_per_evaluation
    monkeypatch.setattr(partners_module, "PARTNERS_AFTER_WORK", 300 * work)
    together = alternating_greedy_search(task, SearchBudget(None, None))
    monkeypatch.setattr(partners_module, "PARTNERS_AFTER_WORK", 10**30)
    alone = alternating_greedy_search(task, SearchBudget(None, None))
    assert alone.plan == alone_runs[0].plan and alone.evaluated == alone_runs[0].evaluated
    winner, evaluations = _turns([run.evaluated for run in alone_runs], 300,
                                 partners_module.PARTNER_TURN_EVALUATIONS)
    assert winner != 0
    assert together.plan == alone_runs[winner].plan and together.evaluated == sum(evaluations)


def test_more_partners_than_the_c_search_holds_are_refused(library: object) -> None:
    task = _load("pegsol", "task13.pddl")
    with pytest.raises(ValueError, match="at most 7 partners"):
        _portfolio(task, library, (H_FF_ALONE,) * 8, 10, 10)
