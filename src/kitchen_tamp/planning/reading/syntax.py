"""What a domain or problem file says, as plain records: the meeting point of our two readers.

``pddl_files`` fills these records from the ``pddl`` package's objects and
``strips_text_reader`` fills them straight from the text; ``schemas`` checks
and translates them, whichever reader produced them. They hold names as
spelled in the file and nothing is checked yet beyond the grammar.

A literal is ``(positive, predicate, terms)``: ``predicate`` is ``"="`` for an
equality, and a term that starts with ``?`` is a variable. A typed name is
``(name, types)`` with ``types`` the declared type names, ``("object",)`` when
none is given (``either`` gives several).
"""

from __future__ import annotations

from kitchen_tamp.planning.frozen_record import FrozenRecord

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    SyntaxLiteral = tuple[bool, str, tuple[str, ...]]
    TypedName = tuple[str, frozenset[str]]

ROOT_TYPE = "object"
EQUALITY = "="


class ActionSyntax(FrozenRecord):
    """An action as written: parameters without their ``?``, and the literals of its
    precondition and effect in file order (conjunctions flattened)."""

    __slots__ = ("name", "parameters", "precondition", "effect")  # noqa: RUF023 (the order of __init__)
    name: str
    parameters: tuple[TypedName, ...]
    precondition: tuple[SyntaxLiteral, ...]
    effect: tuple[SyntaxLiteral, ...]

    def __init__(self, name: str, parameters: tuple[TypedName, ...],
                 precondition: tuple[SyntaxLiteral, ...], effect: tuple[SyntaxLiteral, ...]) -> None:
        self._set_fields(name=name, parameters=parameters, precondition=precondition, effect=effect)


class DomainSyntax(FrozenRecord):
    """A domain as written. ``types`` maps each declared type to its parent (None for none);
    ``actions`` are in file order."""

    __slots__ = (  # noqa: RUF023 (the order of __init__)
        "name", "types", "predicates", "constants", "actions"
    )
    name: str
    types: dict[str, str | None]
    predicates: dict[str, int]
    constants: tuple[TypedName, ...]
    actions: tuple[ActionSyntax, ...]

    def __init__(self, name: str, types: dict[str, str | None], predicates: dict[str, int],
                 constants: tuple[TypedName, ...], actions: tuple[ActionSyntax, ...]) -> None:
        self._set_fields(name=name, types=types, predicates=predicates, constants=constants, actions=actions)


class ProblemSyntax(FrozenRecord):
    """A problem as written: its positive initial facts ``(predicate, arguments)`` (the
    negative ones are implied by the closed world) and the literals of its goal."""

    __slots__ = ("name", "domain_name", "objects", "init", "goal")  # noqa: RUF023 (the order of __init__)
    name: str
    domain_name: str
    objects: tuple[TypedName, ...]
    init: tuple[tuple[str, tuple[str, ...]], ...]
    goal: tuple[SyntaxLiteral, ...]

    def __init__(self, name: str, domain_name: str, objects: tuple[TypedName, ...],
                 init: tuple[tuple[str, tuple[str, ...]], ...], goal: tuple[SyntaxLiteral, ...]) -> None:
        self._set_fields(name=name, domain_name=domain_name, objects=objects, init=init, goal=goal)
