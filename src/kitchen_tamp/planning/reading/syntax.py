"""What a domain or problem file says, as plain records: the meeting point of our two readers.

``package_reader`` fills these records from the ``pddl`` package's objects and
``strips_text_reader`` fills them straight from the text; ``schemas`` checks
and translates them, whichever reader produced them. They hold names as
spelled in the file and nothing is checked yet beyond the grammar.

A literal is ``(positive, predicate, terms)``: ``predicate`` is ``"="`` for an
equality, and a term that starts with ``?`` is a variable. A typed name is
``(name, types)`` with ``types`` the declared type names, ``("object",)`` when
none is given (``either`` gives several).
"""

from __future__ import annotations

from dataclasses import dataclass

SyntaxLiteral = tuple[bool, str, tuple[str, ...]]
"""``(positive, predicate, terms)``."""

TypedName = tuple[str, frozenset[str]]
"""``(name, types)``."""

ROOT_TYPE = "object"
EQUALITY = "="


@dataclass(frozen=True, slots=True)
class ActionSyntax:
    """An action as written: parameters without their ``?``, and the literals of its
    precondition and effect in file order (conjunctions flattened)."""

    name: str
    parameters: tuple[TypedName, ...]
    precondition: tuple[SyntaxLiteral, ...]
    effect: tuple[SyntaxLiteral, ...]


@dataclass(frozen=True, slots=True)
class DomainSyntax:
    """A domain as written. ``types`` maps each declared type to its parent (None for none);
    ``actions`` are in file order."""

    name: str
    types: dict[str, str | None]
    predicates: dict[str, int]
    constants: tuple[TypedName, ...]
    actions: tuple[ActionSyntax, ...]


@dataclass(frozen=True, slots=True)
class ProblemSyntax:
    """A problem as written: its positive initial facts ``(predicate, arguments)`` (the
    negative ones are implied by the closed world) and the literals of its goal."""

    name: str
    domain_name: str
    objects: tuple[TypedName, ...]
    init: tuple[tuple[str, tuple[str, ...]], ...]
    goal: tuple[SyntaxLiteral, ...]
