"""Reading PDDL files with the ``pddl`` package, with errors that name the place.

The ``pddl`` package parses; it does not check that a problem only uses the
domain's predicates and objects, nor that an action only uses its own
parameters. ``schemas`` does that, on the ``reading.syntax`` records that
``domain_syntax`` and ``problem_syntax`` here make of the package's objects,
using ``PddlSource.locate`` to find the line of the offending name.

This is the reader of every file ``strips_text_reader`` leaves alone, and of
every file with a mistake: its errors are the ones users see.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, TypeVar

from lark import Lark
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedToken
from pddl.core import Domain, Problem
from pddl.logic.base import And, Formula, Not
from pddl.logic.predicates import EqualTo, Predicate
from pddl.logic.terms import Term, Variable
from pddl.parser.domain import DomainTransformer
from pddl.parser.problem import ProblemTransformer

from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.reading.grammar_cache import StartSymbol, parse_with, pddl_parser
from kitchen_tamp.planning.reading.source import PddlSource, read_pddl
from kitchen_tamp.planning.reading.syntax import (
    EQUALITY,
    ROOT_TYPE,
    ActionSyntax,
    DomainSyntax,
    ProblemSyntax,
)

if TYPE_CHECKING:
    from kitchen_tamp.planning.reading.syntax import SyntaxLiteral, TypedName

T = TypeVar("T")

def _syntax_error(error: Exception, path: str | Path, what: str) -> PlanningInputError:
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


def _parse(path: str | Path, text: str, what: str, parser: Callable[[str], T]) -> tuple[T, PddlSource]:
    try:
        parsed = parser(text)
    except Exception as error:  # lark's syntax errors and the pddl package's own checks
        raise _syntax_error(error, path, what) from None
    return parsed, PddlSource(path, text)


def parse_domain(path: Path) -> tuple[Domain, PddlSource]:
    """Parse a domain file; a syntax error names file, line and column."""
    return parse_domain_text(path, read_pddl(path, "domain"))


def parse_domain_text(path: str | Path, text: str) -> tuple[Domain, PddlSource]:
    """Parse a domain already read from ``path``; a syntax error names file, line and column."""
    return _parse(path, text, "domain", _parse_domain_text)


def parse_problem_text(path: str | Path, text: str) -> tuple[Problem, PddlSource]:
    """Parse a problem already read from ``path``; a syntax error names file, line and column."""
    return _parse(path, text, "problem", _parse_problem_text)


def parse_problem(path: Path) -> tuple[Problem, PddlSource]:
    """Parse a problem file; a syntax error names file, line and column."""
    return _parse(path, read_pddl(path, "problem"), "problem", _parse_problem_text)


def _type_tags(term: Term) -> frozenset[str]:
    return frozenset(str(t) for t in term.type_tags) or frozenset({ROOT_TYPE})


def _typed(term: Term) -> TypedName:
    return str(term.name), _type_tags(term)


def _term(term: Term) -> str:
    return "?" + str(term.name) if isinstance(term, Variable) else str(term.name)


def _literal(positive: bool, atom: Predicate | EqualTo) -> SyntaxLiteral:
    if isinstance(atom, EqualTo):
        return positive, EQUALITY, (_term(atom.left), _term(atom.right))
    return positive, str(atom.name), tuple(_term(t) for t in atom.terms)


def _flatten(formula: Formula | None, where: str, src: PddlSource, after: str | None) -> list[SyntaxLiteral]:
    """Flatten a conjunction of literals; anything else is an input error."""
    if formula is None:
        return []
    if isinstance(formula, And):
        out: list[SyntaxLiteral] = []
        for operand in formula.operands:
            out.extend(_flatten(operand, where, src, after))
        return out
    if isinstance(formula, Not) and isinstance(formula.argument, Predicate | EqualTo):
        return [_literal(False, formula.argument)]
    if isinstance(formula, Predicate | EqualTo):
        return [_literal(True, formula)]
    kind = type(formula).__name__
    raise src.error(
        f"{where}: '{kind}' is not supported (STRIPS conjunctions of literals, "
        "negative literals and equality only)", after)


def _action_position(source: PddlSource, name: str) -> int:
    """Where ``(:action name`` starts in the file, so actions keep their file order."""
    found = re.search(r"\(\s*:action\s+" + re.escape(name) + r"(?![\w\-])", source.text, re.IGNORECASE)
    return found.start() if found else len(source.text)


def _action(action: object, source: PddlSource) -> ActionSyntax:
    name = str(action.name)  # type: ignore[attr-defined]
    where, after = f"action '{name}'", f":action {name}"
    return ActionSyntax(
        name,
        tuple(_typed(v) for v in action.parameters),  # type: ignore[attr-defined]
        tuple(_flatten(action.precondition, where, source, after)),  # type: ignore[attr-defined]
        tuple(_flatten(action.effect, where, source, after)),  # type: ignore[attr-defined]
    )


def domain_syntax(domain: Domain, source: PddlSource) -> DomainSyntax:
    """The records of what ``domain`` says; a formula outside STRIPS is an input error."""
    actions = sorted(domain.actions, key=lambda a: (_action_position(source, str(a.name)), str(a.name)))
    return DomainSyntax(
        str(domain.name),
        {str(k): (str(v) if v is not None else None) for k, v in domain.types.items()},
        {str(p.name): p.arity for p in domain.predicates},
        tuple(_typed(c) for c in domain.constants),
        tuple(_action(action, source) for action in actions),
    )


def problem_syntax(problem: Problem, source: PddlSource) -> ProblemSyntax:
    """The records of what ``problem`` says; a fact or goal outside STRIPS is an input error."""
    init = []
    for fact in problem.init:
        if isinstance(fact, Not):
            continue  # closed world: negative facts are implied
        if not isinstance(fact, Predicate):
            raise source.error(f"problem :init: only atoms are allowed here, not '{fact}'", ":init")
        init.append(_literal(True, fact)[1:])
    goal = _flatten(problem.goal, "problem :goal", source, ":goal")
    for _, predicate, _ in goal:
        if predicate == EQUALITY:
            raise source.error("problem :goal: equality is not supported in goals", ":goal")
    return ProblemSyntax(str(problem.name), str(problem.domain_name),
                         tuple(_typed(o) for o in problem.objects), tuple(init), tuple(goal))
