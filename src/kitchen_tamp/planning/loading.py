"""From PDDL files to a grounded ``Task``: parse, translate, ground; each domain is translated once.

Parsing the domain with the ``pddl`` package is the largest cost of loading a
small task once its Lark parsers are loaded (see ``grammar_cache``): the
parser runs in pure Python, ~2 ms for the kitchen domain, and a process often
loads many problems of one domain (the bilevel planner, the benchmarks, the
tests). So the checked ``DomainModel`` is kept per
(path, text): a domain file that has not changed is not parsed again.
``clear_domain_cache`` forgets them, e.g. to time cold loads.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from kitchen_tamp.planning.grounding import ground
from kitchen_tamp.planning.pddl_files import parse_domain_text, parse_problem
from kitchen_tamp.planning.pddl_paths import read_pddl, resolve_problem_path
from kitchen_tamp.planning.schemas import DomainModel, translate_problem
from kitchen_tamp.planning.task import Task

DOMAIN_CACHE_SIZE = 32


@lru_cache(maxsize=DOMAIN_CACHE_SIZE)
def _domain_model(path: Path, text: str) -> DomainModel:
    domain, source = parse_domain_text(path, text)
    return DomainModel(domain, source)


def domain_model(path: Path) -> DomainModel:
    """The checked domain in ``path``, translated once per file content."""
    return _domain_model(path, read_pddl(path, "domain"))


def clear_domain_cache() -> None:
    """Forget every translated domain, so the next load parses its domain again."""
    _domain_model.cache_clear()


def load_task(problem_path: str | Path, domain_path: str | Path | None = None) -> Task:
    """Parse, check and ground a PDDL problem.

    A bare problem file name that does not exist in the current directory is
    looked up in the repository's ``pddl/``; the domain defaults to
    ``domain.pddl`` beside the problem. Raises ``PlanningInputError`` for any
    problem with the files.
    """
    problem_file = resolve_problem_path(problem_path)
    domain_file = Path(domain_path) if domain_path is not None else problem_file.parent / "domain.pddl"
    problem, psrc = parse_problem(problem_file)
    return ground(translate_problem(domain_model(domain_file), problem, psrc))
