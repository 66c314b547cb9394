"""The fast STRIPS reader against the ``pddl`` package: whatever it reads, it reads as the package does.

Two claims, checked on every PDDL file the project ships and on seeded mutations of them (a
token deleted, doubled, swapped, replaced by another token of the file or by a word of the
grammar, upper-cased, a parenthesis dropped):
- a file the fast reader takes, the package takes too, with the same records;
- loading a task gives the same ``Task`` or the same error message, to the character, as
  loading it with the package alone.
And the fast reader must take the files we plan on every day, or it would speed nothing up.
"""

from __future__ import annotations

import random
import re
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from kitchen_tamp.planning import loading
from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.reading.package_reader import (
    domain_syntax,
    parse_domain_text,
    parse_problem_text,
    problem_syntax,
)
from kitchen_tamp.planning.reading.strips_text_reader import read_domain_text, read_problem_text
from kitchen_tamp.planning.reading.syntax import DomainSyntax, ProblemSyntax
from kitchen_tamp.planning.task import Task
from tests.planning.conftest import DATA, KITCHEN, REPO

if TYPE_CHECKING:
    from kitchen_tamp.planning.reading.syntax import SyntaxLiteral

IPC = REPO / "benchmarks" / "ipc"

PAIRS = [
    *((KITCHEN / name, KITCHEN / "domain.pddl") for name in ("problem.pddl", "problem_hard.pddl",
                                                              "problem_baguette.pddl")),
    *((DATA / problem, DATA / domain) for problem, domain in (
        ("blocks_sussman.pddl", "blocks_domain.pddl"), ("delivery_two_parcels.pddl", "delivery_domain.pddl"),
        ("dead_end_problem.pddl", "dead_end_domain.pddl"), ("achiever_problem.pddl", "achiever_domain.pddl"),
        ("helpful_trap_problem.pddl", "helpful_trap_domain.pddl"))),
    *((problem, problem.parent / "domain.pddl") for problem in sorted(IPC.glob("*/*.pddl"))
      if not problem.name.startswith("domain")
      and not (problem.parent / ("domain" + problem.name.removeprefix("task"))).exists()),
    *((problem, problem.parent / ("domain" + problem.name.removeprefix("task")))
      for problem in sorted(IPC.glob("*/task*.pddl"))
      if (problem.parent / ("domain" + problem.name.removeprefix("task"))).exists()),
]
"""(problem, domain) pairs: the kitchen, the test data and the IPC problems of the benchmark."""

MUTATED_PAIRS = [
    pair for index, pair in enumerate(PAIRS)
    if pair[0].parent != pair[1].parent or IPC not in pair[0].parents
    or all(other[0].parent != pair[0].parent for other in PAIRS[:index])
]
"""The pairs the mutation test mutates: the kitchen, the test data and the first problem of each IPC
domain (every domain's kinds of text, at a fraction of the cost of all its problems)."""

GRAMMAR_TOKENS = ["(", ")", "-", "?", "=", "?x", "and", "not", "or", "either", "object", "define", ":adl",
                  ":typing", ":equality", ":strips", ":negative-preconditions", ":init", ":goal",
                  ":objects", ":types", ":constants", ":predicates", ":action", ":parameters",
                  ":precondition", ":effect", ":requirements", "()", "1", "a;b", "x:y", "AND", "Object"]


def _pddl_domain(path: Path, text: str) -> DomainSyntax:
    domain, source = parse_domain_text(path, text)
    return domain_syntax(domain, source)


def _pddl_problem(path: Path, text: str) -> ProblemSyntax:
    problem, source = parse_problem_text(path, text)
    return problem_syntax(problem, source)


def _once(literals: tuple[SyntaxLiteral, ...]) -> list[SyntaxLiteral]:
    """Literals without repeats (the package's conjunctions drop them; ``schemas`` does for both)."""
    first: dict[object, SyntaxLiteral] = {}
    for positive, predicate, terms in literals:
        key = (positive, predicate.lower(), tuple(t.lower() for t in terms))
        first.setdefault(key, (positive, predicate, terms))
    return list(first.values())


def _normal(record: DomainSyntax | ProblemSyntax) -> object:
    """A record with the package's set-ordered collections sorted and repeated literals dropped."""
    if isinstance(record, DomainSyntax):
        actions = [(a.name, a.parameters, _once(a.precondition), _once(a.effect)) for a in record.actions]
        return (record.name, record.types, record.predicates, sorted(record.constants, key=str), actions)
    init = {(p.lower(), tuple(a.lower() for a in args)) for p, args in record.init}  # a set in the package
    return (record.name, record.domain_name, sorted(record.objects, key=str), sorted(init),
            _once(record.goal))


def _tokens(text: str) -> list[str]:
    return re.findall(r"\(|\)|[^\s()]+", re.sub(r";[^\n]*", "", text))


def _mutant(tokens: list[str], rng: random.Random) -> str:
    mutated = list(tokens)
    i = rng.randrange(len(mutated))
    kind = rng.randrange(6)
    if kind == 0:
        del mutated[i]
    elif kind == 1:
        mutated.insert(i, mutated[i])
    elif kind == 2 and i + 1 < len(mutated):
        mutated[i], mutated[i + 1] = mutated[i + 1], mutated[i]
    elif kind == 3:
        mutated[i] = rng.choice(tokens)
    elif kind == 4:
        mutated[i] = rng.choice(GRAMMAR_TOKENS)
    else:
        mutated[i] = mutated[i].upper()
    return " ".join(mutated)


def _outcome(problem: Path, domain: Path) -> Task | str:
    loading.clear_domain_cache()
    try:
        return loading.load_task(problem, domain)
    except PlanningInputError as error:
        return str(error)


@pytest.mark.parametrize(("problem", "domain"), PAIRS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_the_fast_reader_takes_the_files_we_ship_and_reads_them_as_the_package_does(
        problem: Path, domain: Path) -> None:
    domain_text, problem_text = domain.read_text(), problem.read_text()
    fast_domain, fast_problem = read_domain_text(domain_text), read_problem_text(problem_text)
    if IPC in problem.parents and (fast_domain is None or fast_problem is None):
        # Benchmark files written otherwise than the package's grammar asks (Windows line endings,
        # capitals) are left to the package, which must read them.
        assert not isinstance(_outcome(problem, domain), str)
        return
    assert fast_domain is not None and fast_problem is not None
    assert _normal(fast_domain) == _normal(_pddl_domain(domain, domain_text))
    assert _normal(fast_problem) == _normal(_pddl_problem(problem, problem_text))


def test_either_in_a_domains_variables_is_read_as_the_package_reads_it() -> None:
    domain = IPC / "zenotravel" / "domain.pddl"  # (at ?x - (either person aircraft) ?c - city)
    text = domain.read_text()
    either = "(either person aircraft)"
    assert either in text
    taken = {
        "as shipped": text,
        "one type": text.replace(either, "(either person)"),
        "a type twice": text.replace(either, "(either person person)"),
        "an action's parameter": text.replace("(?p - person ?a - aircraft ?c - city)",
                                              "(?p - (either person aircraft) ?a - aircraft ?c - city)", 1),
    }
    for what, variant in taken.items():
        fast = read_domain_text(variant)
        assert fast is not None, what
        assert _normal(fast) == _normal(_pddl_domain(domain, variant)), what
    left = {  # each refused by the package, or (the last two) outside what the fast reader reads
        "object among the types": text.replace(either, "(either object person)"),
        "an undeclared type": text.replace(either, "(either person plane)"),
        "no type": text.replace(either, "(either)"),
        "without :typing": text.replace("(:requirements :typing)", "(:requirements :strips)"),
        "a capital keyword": text.replace(either, "(EITHER person aircraft)"),
        "in the types": text.replace("flevel - object", "flevel - (either object city)"),
    }
    for what, variant in left.items():
        assert read_domain_text(variant) is None, what


@pytest.mark.slow
def test_a_mutated_file_is_read_as_the_package_reads_it_or_left_to_it(tmp_path: Path) -> None:
    rng = random.Random(20261130)
    taken = left = 0
    for problem, domain in MUTATED_PAIRS:
        if problem.stat().st_size > 20_000:
            continue  # mystery-10: large, and its domain is covered through the others' kinds of mistakes
        for path, read, package_read in ((domain, read_domain_text, _pddl_domain),
                                         (problem, read_problem_text, _pddl_problem)):
            tokens = _tokens(path.read_text())
            for _ in range(200):
                text = " ".join(tokens)
                for _ in range(rng.choice((1, 1, 2, 3))):
                    text = _mutant(_tokens(text), rng)
                fast = read(text)  # type: ignore[operator]
                if fast is None:
                    left += 1
                    continue
                taken += 1
                try:
                    expected = package_read(path, text)
                except PlanningInputError as error:
                    pytest.fail(f"the fast reader took a mutant of {path.name} that the package refuses "
                                f"({error}):\n{text}")
                assert _normal(fast) == _normal(expected), text
    assert taken > 500 and left > 500  # the mutations reach both sides


@pytest.mark.slow
def test_loading_gives_the_same_task_or_the_same_error_as_the_package_alone(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(7)
    cases: list[tuple[str, str]] = []
    for problem, domain in PAIRS[:5]:
        domain_text, problem_text = domain.read_text(), problem.read_text()
        cases.append((domain_text, problem_text))
        for _ in range(60):
            cases.append((_mutant(_tokens(domain_text), rng), problem_text))
            cases.append((domain_text, _mutant(_tokens(problem_text), rng)))
    domain_file, problem_file = tmp_path / "domain.pddl", tmp_path / "problem.pddl"
    outcomes = []
    for domain_text, problem_text in cases:
        domain_file.write_text(domain_text)
        problem_file.write_text(problem_text)
        with_fast = _outcome(problem_file, domain_file)
        with monkeypatch.context() as patched:
            patched.setattr(loading, "read_domain_text", lambda text: None)
            patched.setattr(loading, "read_problem_text", lambda text: None)
            package_alone = _outcome(problem_file, domain_file)
        assert with_fast == package_alone, (domain_text, problem_text)
        outcomes.append(isinstance(with_fast, Task))
    assert sum(outcomes) > 50 and outcomes.count(False) > 50  # tasks and errors both compared
