"""The text of a PDDL file as the fast reader sees it: one parenthesised expression as nested lists
of tokens, and the names, variables, typed lists and sections in it, each refused (``Unsupported``)
wherever the ``pddl`` package might read it otherwise (``strips_text_reader`` reads the sections)."""

from __future__ import annotations

from collections.abc import Callable

from kitchen_tamp.planning.reading.syntax import ROOT_TYPE

Expression = str | list["Expression"]
"""A token, or a parenthesised list of expressions."""

GRAMMAR_WORDS = frozenset({
    "define", "domain", "problem", "either", "object", "and", "or", "not", "imply", "forall", "exists",
    "when", "oneof", "assign", "scale-up", "scale-down", "increase", "decrease", "maximize", "minimize",
    "total-cost", "number",
})
"""The words of the ``pddl`` package's grammar; a file using one as a name is left to the package."""


class Unsupported(Exception):
    """Raised inside the reader when a file is not one it reads; the public functions answer None."""


def single_expression(text: str) -> list[Expression]:
    """The one parenthesised expression ``text`` holds, as nested lists of tokens."""
    if not text.isascii():
        raise Unsupported
    lines = text.split("\n")
    for index, line in enumerate(lines):
        cut = line.find(";")
        if cut >= 0:
            if cut > 0 and line[cut - 1] not in " \t\r\f\v()":
                raise Unsupported  # the package's lexer would read the ';' as part of a name
            lines[index] = line[:cut]
    tokens = " ".join(lines).replace("(", " ( ").replace(")", " ) ").split()
    stack: list[list[Expression]] = [[]]
    for token in tokens:
        if token == "(":
            opened: list[Expression] = []
            stack[-1].append(opened)
            stack.append(opened)
        elif token == ")":
            if len(stack) == 1:
                raise Unsupported
            stack.pop()
        else:
            stack[-1].append(token)
    top = stack[0]
    if len(stack) != 1 or len(top) != 1 or not isinstance(top[0], list):
        raise Unsupported
    return top[0]


def is_name(token: Expression) -> bool:
    """Whether ``token`` is a name the package accepts: a letter, then letters, digits, '-' or '_'."""
    return (isinstance(token, str) and token[:1].isalpha()
            and token.replace("-", "").replace("_", "").isalnum()
            and token.lower() not in GRAMMAR_WORDS)


def read_name(token: Expression) -> str:
    if not is_name(token):
        raise Unsupported
    assert isinstance(token, str)
    return token


def read_variable(token: Expression) -> str:
    """A variable's name, without its ``?``."""
    if not isinstance(token, str) or token[0] != "?" or not is_name(token[1:]):
        raise Unsupported
    return token[1:]


def read_type_name(token: Expression) -> str:
    if token == ROOT_TYPE:
        return ROOT_TYPE
    return read_name(token)


def read_either(token: Expression) -> tuple[str, ...]:
    """The types of ``(either t1 t2 ...)``: at least one, lowercase keyword, none of them ``object``
    (the package refuses it in a domain's typed list, ``either`` or not)."""
    if not isinstance(token, list) or len(token) < 2 or token[0] != "either":
        raise Unsupported
    names = tuple(read_name(name) for name in token[1:])
    if any(name.lower() == ROOT_TYPE for name in names):
        raise Unsupported
    return names


def read_typed_list(
    items: list[Expression], read: Callable[[Expression], str], either: bool = False
) -> list[tuple[str, tuple[str, ...] | None]]:
    """``a b - t c`` as ``[(a, (t,)), (b, (t,)), (c, None)]``, and with ``either`` (a domain's variables)
    ``a - (either t u)`` as ``[(a, (t, u))]``; a name twice (in any case) is left to the package."""
    typed: list[tuple[str, tuple[str, ...] | None]] = []
    pending: list[str] = []
    index = 0
    while index < len(items):
        item = items[index]
        if item == "-":
            if not pending or index + 1 >= len(items):
                raise Unsupported
            token = items[index + 1]
            types = read_either(token) if either and isinstance(token, list) else (read_type_name(token),)
            typed.extend((name, types) for name in pending)
            pending = []
            index += 2
        else:
            pending.append(read(item))
            index += 1
    typed.extend((name, None) for name in pending)
    if len({name.lower() for name, _ in typed}) != len(typed):
        raise Unsupported
    return typed


def type_tags(types: tuple[str, ...] | None) -> frozenset[str]:
    return frozenset(types or (ROOT_TYPE,))


def read_section(expression: Expression) -> tuple[str, list[Expression]]:
    """A section ``(:keyword ...)`` as its keyword and the rest."""
    if not isinstance(expression, list) or not expression or not isinstance(expression[0], str):
        raise Unsupported
    return expression[0], expression[1:]


def read_header(expression: Expression, word: str) -> str:
    """The name in ``(domain NAME)`` or ``(problem NAME)``."""
    if not isinstance(expression, list) or len(expression) != 2 or expression[0] != word:
        raise Unsupported
    return read_name(expression[1])
