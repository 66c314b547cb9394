"""Reading PDDL files with the ``pddl`` package, with errors that name the place.

The ``pddl`` package parses; it does not check that a problem only uses the
domain's predicates and objects, nor that an action only uses its own
parameters. ``grounding`` does that, using ``locate`` here to find the line of
the offending name in the file text.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import TypeVar

from lark import Lark
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedToken
from pddl.core import Domain, Problem
from pddl.parser.domain import DomainTransformer
from pddl.parser.problem import ProblemTransformer

from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.grammar_cache import StartSymbol, parse_with, pddl_parser
from kitchen_tamp.planning.pddl_paths import read_pddl
from kitchen_tamp.planning.pddl_paths import resolve_problem_path as resolve_problem_path

T = TypeVar("T")

@dataclass(frozen=True)
class PddlSource:
    """A parsed PDDL file with its text, kept for error messages."""

    path: Path
    text: str

    def locate(self, name: str, after: str | None = None) -> tuple[int | None, int | None]:
        """Line and column of the first whole-word ``name`` (after ``after`` if given)."""
        start = 0
        if after is not None:
            found = re.search(re.escape(after), self.text, re.IGNORECASE)
            start = found.start() if found else 0
        pattern = r"(?<![\w\-?])" + re.escape(name) + r"(?![\w\-])"
        match = re.compile(pattern, re.IGNORECASE).search(self.text, start)
        if match is None:
            return None, None
        line = self.text.count("\n", 0, match.start()) + 1
        column = match.start() - (self.text.rfind("\n", 0, match.start()) + 1) + 1
        return line, column

    def error(self, message: str, name: str | None = None, after: str | None = None) -> PlanningInputError:
        """An input error placed at ``name``'s first occurrence, if found."""
        line, column = self.locate(name, after) if name else (None, None)
        return PlanningInputError(message, self.path, line, column)


def _syntax_error(error: Exception, path: Path, what: str) -> PlanningInputError:
    line = getattr(error, "line", None)
    column = getattr(error, "column", None)
    if isinstance(error, UnexpectedToken):
        token = "end of file" if error.token.type == "$END" else repr(str(error.token))
        expected = ", ".join(sorted(error.expected)[:6])
        message = f"{what} syntax error: unexpected {token}, expected one of {expected}"
        if error.token.type == "$END":
            message = f"{what} syntax error: file ends early (unbalanced parentheses?)"
    elif isinstance(error, UnexpectedCharacters):
        message = f"{what} syntax error: unexpected {error.char!r}"
    elif isinstance(error, UnexpectedEOF):
        message = f"{what} syntax error: file ends early (unbalanced parentheses?)"
    else:
        first_line = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
        message = f"invalid {what}: {first_line}"
    if isinstance(line, int) and line < 1:
        line = column = None
    return PlanningInputError(message, path, line if isinstance(line, int) else None,
                              column if isinstance(column, int) else None)


@cache
def _lark_parser(start: StartSymbol) -> Lark:
    """Each process loads each parser once (from the grammar cache, see ``grammar_cache``)."""
    return pddl_parser(start)


def _parse_domain_text(text: str) -> Domain:
    return parse_with(_lark_parser("domain"), DomainTransformer(), text)


def _parse_problem_text(text: str) -> Problem:
    return parse_with(_lark_parser("problem"), ProblemTransformer(), text)


def _parse(path: Path, text: str, what: str, parser: Callable[[str], T]) -> tuple[T, PddlSource]:
    try:
        parsed = parser(text)
    except Exception as error:  # lark's syntax errors and the pddl package's own checks
        raise _syntax_error(error, path, what) from None
    return parsed, PddlSource(path, text)


def parse_domain(path: Path) -> tuple[Domain, PddlSource]:
    """Parse a domain file; a syntax error names file, line and column."""
    return parse_domain_text(path, read_pddl(path, "domain"))


def parse_domain_text(path: Path, text: str) -> tuple[Domain, PddlSource]:
    """Parse a domain already read from ``path``; a syntax error names file, line and column."""
    return _parse(path, text, "domain", _parse_domain_text)


def parse_problem(path: Path) -> tuple[Problem, PddlSource]:
    """Parse a problem file; a syntax error names file, line and column."""
    return _parse(path, read_pddl(path, "problem"), "problem", _parse_problem_text)
