"""From PDDL files to a grounded ``Task``: read, check, translate, ground; each domain is translated once.

Each file is read by ``strips_text_reader`` when it can (the STRIPS files we
plan on, in a millisecond or two without importing Lark or the ``pddl``
package), and otherwise by the ``pddl`` package (``reading.package_reader``). A file the
fast reader takes but ``schemas`` finds a mistake in is read again by the
``pddl`` package, so every error a user sees comes from the package's reading,
as it did before the fast reader existed.

The checked ``DomainModel`` is kept per (path, text): a process often loads
many problems of one domain (the bilevel planner, the benchmarks, the tests),
and a domain file that has not changed is not read again.
``clear_domain_cache`` forgets them, e.g. to time cold loads.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.grounding import ground
from kitchen_tamp.planning.reading.source import PddlSource, read_pddl
from kitchen_tamp.planning.reading.strips_text_reader import read_domain_text, read_problem_text
from kitchen_tamp.planning.reading.syntax import ProblemSyntax
from kitchen_tamp.planning.schemas import DomainModel, LiftedTask, translate_problem
from kitchen_tamp.planning.task import Task

DOMAIN_FILE = "domain.pddl"
"""The domain a problem file goes with when none is named: this file beside it."""

DOMAIN_CACHE_SIZE = 32


@lru_cache(maxsize=DOMAIN_CACHE_SIZE)
def _domain_model(path: str | Path, text: str) -> DomainModel:
    syntax = read_domain_text(text)
    if syntax is not None:
        try:
            return DomainModel(syntax, PddlSource(path, text))
        except PlanningInputError:
            pass  # read again below, so that the pddl package's reading words the error
    from kitchen_tamp.planning.reading.package_reader import (  # imports Lark and pddl
        domain_syntax,
        parse_domain_text,
    )

    domain, source = parse_domain_text(path, text)
    return DomainModel(domain_syntax(domain, source), source)


def domain_model(path: str | Path) -> DomainModel:
    """The checked domain in ``path``, translated once per file content."""
    return _domain_model(path, read_pddl(path, "domain"))


def clear_domain_cache() -> None:
    """Forget every translated domain, so the next load reads its domain again."""
    _domain_model.cache_clear()


def _problem_with_pddl_package(path: str | Path, text: str) -> tuple[ProblemSyntax, PddlSource]:
    from kitchen_tamp.planning.reading.package_reader import (  # imports Lark and pddl
        parse_problem_text,
        problem_syntax,
    )

    problem, source = parse_problem_text(path, text)
    return problem_syntax(problem, source), source


def read_problem(path: str | Path) -> tuple[ProblemSyntax, PddlSource, bool]:
    """The problem's records and text, and whether the fast reader produced them; a syntax
    error (from the ``pddl`` package) names file, line and column."""
    text = read_pddl(path, "problem")
    fast = read_problem_text(text)
    if fast is not None:
        return fast, PddlSource(path, text), True
    return (*_problem_with_pddl_package(path, text), False)


def lifted_task(problem_path: str | Path, domain_path: str | Path) -> LiftedTask:
    """Read and check a problem and its domain: the problem's syntax errors come first, then
    the domain's, then the names the problem uses."""
    problem, source, fast = read_problem(problem_path)
    try:
        return translate_problem(domain_model(domain_path), problem, source)
    except PlanningInputError:
        if not fast:
            raise
    # The fast reader took a file with a mistake: the pddl package's reading words the error.
    problem, source = _problem_with_pddl_package(problem_path, source.text)
    return translate_problem(domain_model(domain_path), problem, source)


def default_domain(problem_path: str | Path) -> Path:
    """The domain file of a problem when none is named: ``domain.pddl`` beside it."""
    return Path(problem_path).parent / DOMAIN_FILE


def load_task(problem_path: str | Path, domain_path: str | Path | None = None) -> Task:
    """Parse, check and ground a PDDL problem.

    The paths are taken as given (a caller that looks bare names up somewhere,
    such as the command lines in the shipped kitchens, does so first); the
    domain defaults to ``domain.pddl`` beside the problem. Raises
    ``PlanningInputError`` for any problem with the files.
    """
    domain = domain_path if domain_path is not None else default_domain(problem_path)
    return ground(lifted_task(problem_path, domain))
