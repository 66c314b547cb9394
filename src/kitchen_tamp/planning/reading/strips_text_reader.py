"""Reading a STRIPS domain or problem straight from its text, for files the ``pddl`` package accepts.

Importing Lark and the ``pddl`` package and loading their parsers costs about
75 ms, more than pyperplan's whole run on a small problem; the text of a
STRIPS file is a handful of nested lists. This reader covers the fragment we
plan on, written as the ``pddl`` grammar asks (typing, constants, negative
preconditions, equality, conjunctions of literals, sections in the grammar's
order, lowercase keywords), and answers ``None`` for anything else or anything
the package might object to (other requirements, ``either`` outside a domain's
variables, numbers, an empty precondition, a grammar word or a refused pattern used
as a name, a name declared twice, a type cycle, ``- type`` without ``:typing``, ``=``
without ``:equality``, any syntax error: ``pddl_text`` reads the tokens, names and
typed lists). The caller then reads the file with the
``pddl`` package (``package_reader``), which decides and words every error: the
package stays the judge of what a file means, and
``tests/planning/test_strips_text_reader.py`` holds this reader to its reading.
"""

from __future__ import annotations

from collections.abc import Callable

from kitchen_tamp.planning.reading.pddl_text import (
    Expression,
    Unsupported,
    read_header,
    read_name,
    read_section,
    read_typed_list,
    read_variable,
    single_expression,
    type_tags,
)
from kitchen_tamp.planning.reading.syntax import (
    EQUALITY,
    ROOT_TYPE,
    ActionSyntax,
    DomainSyntax,
    ProblemSyntax,
    SyntaxLiteral,
    TypedName,
)

SUPPORTED_REQUIREMENTS = frozenset({":strips", ":typing", ":negative-preconditions", ":equality"})
"""Requirements this reader takes; a file declaring any other is left to the ``pddl`` package."""

DOMAIN_SECTIONS = (":requirements", ":types", ":constants", ":predicates")
"""The domain's optional sections, in the order the grammar requires, before the actions."""


def read_domain_text(text: str) -> DomainSyntax | None:
    """The domain in ``text``, or None when the ``pddl`` package must read it."""
    try:
        return _domain(single_expression(text))
    except Unsupported:
        return None


def read_problem_text(text: str) -> ProblemSyntax | None:
    """The problem in ``text``, or None when the ``pddl`` package must read it."""
    try:
        return _problem(single_expression(text))
    except Unsupported:
        return None


def _requirements(items: list[Expression]) -> frozenset[str]:
    if not items or any(not isinstance(item, str) or item not in SUPPORTED_REQUIREMENTS for item in items):
        raise Unsupported
    return frozenset(item for item in items if isinstance(item, str))


class _DomainReader:
    """The state of reading one domain: what is declared so far."""

    def __init__(self, check_constants: bool) -> None:
        self.check_constants = check_constants
        """Whether a name in a literal must be a declared constant (in a domain, not in a goal)."""
        self.constant_names: dict[str, str] = {}
        """The declared constants, by lowercase name."""
        self.requirements: frozenset[str] = frozenset()
        self.types: dict[str, str | None] = {}
        self.known_types: set[str] = set()
        """The types the package knows (declared, or a declared type's parent), in lowercase."""
        self.constants: tuple[TypedName, ...] = ()
        self.predicates: dict[str, int] = {}
        self.parameters: dict[str, str] = {}
        """The current action's parameters, by lowercase name, as declared."""

    def typed(self, items: list[Expression], read: Callable[[Expression], str],
              either: bool = False) -> list[tuple[str, tuple[str, ...] | None]]:
        typed = read_typed_list(items, read, either)
        if ":typing" not in self.requirements and any(types is not None for _, types in typed):
            raise Unsupported  # the package requires :typing for a typed list
        return typed

    def read_types(self, items: list[Expression]) -> None:
        if ":typing" not in self.requirements:
            raise Unsupported
        for name, types in self.typed(items, read_name):
            parent = None if types is None else types[0]
            self.types[name] = None if parent is None or parent.lower() == ROOT_TYPE else parent
        lowered = {name.lower(): (parent.lower() if parent else None) for name, parent in self.types.items()}
        self.known_types = set(lowered) | {parent for parent in lowered.values() if parent}
        for start in lowered:
            seen = {start}
            current = lowered[start]
            while current is not None:
                if current in seen:
                    raise Unsupported  # a cycle in the type hierarchy
                seen.add(current)
                current = lowered.get(current)

    def check_type_known(self, types: tuple[str, ...] | None) -> None:
        """Types the package knows: declared, or a declared type's parent. (It refuses ``- object``
        in a domain: its types drop ``object`` as a parent.)"""
        if any(type_name.lower() not in self.known_types for type_name in types or ()):
            raise Unsupported

    def read_predicates(self, items: list[Expression]) -> None:
        if not items:
            raise Unsupported
        declared: set[str] = set()
        for item in items:
            if not isinstance(item, list) or not item:
                raise Unsupported
            name = read_name(item[0])
            if name.lower() in declared:
                raise Unsupported
            declared.add(name.lower())
            parameters = self.typed(item[1:], read_variable, either=True)
            for _, types in parameters:
                self.check_type_known(types)
            self.predicates[name] = len(parameters)

    def term(self, token: Expression) -> str:
        """A constant or variable (``?`` included) spelled as declared, as the package spells them."""
        if isinstance(token, str) and token.startswith("?"):
            variable = read_variable(token)
            return "?" + self.parameters.get(variable.lower(), variable)
        name = read_name(token)
        if not self.check_constants:
            return name
        declared = self.constant_names.get(name.lower())
        if declared is None:
            raise Unsupported  # the package refuses a domain's undeclared constant
        return declared

    def atom(self, expression: Expression, positive: bool, out: list[SyntaxLiteral]) -> None:
        """A literal ``(p t1 .. tn)`` or ``(= t1 t2)``."""
        if not isinstance(expression, list) or not expression:
            raise Unsupported
        head = expression[0]
        if head == EQUALITY:
            if ":equality" not in self.requirements or len(expression) != 3:
                raise Unsupported
        else:
            head = read_name(head)
        assert isinstance(head, str)
        out.append((positive, head, tuple(self.term(term) for term in expression[1:])))

    def condition(self, expression: Expression, out: list[SyntaxLiteral]) -> None:
        """A conjunction of literals, nested conjunctions flattened."""
        if not isinstance(expression, list) or not expression:
            raise Unsupported
        if expression[0] == "and":
            for operand in expression[1:]:
                self.condition(operand, out)
        elif expression[0] == "not":
            if len(expression) != 2:
                raise Unsupported
            self.atom(expression[1], False, out)
        else:
            self.atom(expression, True, out)

    def effect(self, expression: Expression, out: list[SyntaxLiteral]) -> None:
        """``(and l1 .. ln)`` or one literal; a literal is an atom or its negation."""
        if not isinstance(expression, list) or not expression:
            raise Unsupported
        literals = expression[1:] if expression[0] == "and" else [expression]
        for literal in literals:
            if not isinstance(literal, list) or not literal or literal[0] == EQUALITY:
                raise Unsupported
            if literal[0] == "not":
                if len(literal) != 2 or not isinstance(literal[1], list) or not literal[1] \
                        or literal[1][0] == EQUALITY:
                    raise Unsupported
                self.atom(literal[1], False, out)
            else:
                self.atom(literal, True, out)

    def action(self, items: list[Expression]) -> ActionSyntax:
        if len(items) < 3 or items[1] != ":parameters" or not isinstance(items[2], list):
            raise Unsupported
        name = read_name(items[0])
        parameters = self.typed(items[2], read_variable, either=True)
        for _, types in parameters:
            self.check_type_known(types)
        self.parameters = {variable.lower(): variable for variable, _ in parameters}
        precondition: list[SyntaxLiteral] = []
        effect: list[SyntaxLiteral] = []
        rest = items[3:]
        if len(rest) >= 2 and rest[0] == ":precondition":
            # An empty '()' is refused there: the package reads it as an empty 'or'.
            self.condition(rest[1], precondition)
            rest = rest[2:]
        if len(rest) >= 2 and rest[0] == ":effect":
            self.effect(rest[1], effect)
            rest = rest[2:]
        if rest:
            raise Unsupported
        return ActionSyntax(name, tuple((variable, type_tags(types)) for variable, types in parameters),
                            tuple(precondition), tuple(effect))


def _domain(expression: list[Expression]) -> DomainSyntax:
    if len(expression) < 2 or expression[0] != "define":
        raise Unsupported
    name = read_header(expression[1], "domain")
    reader = _DomainReader(check_constants=True)
    actions: list[ActionSyntax] = []
    next_section = 0
    for section in expression[2:]:
        keyword, items = read_section(section)
        if keyword == ":action":
            actions.append(reader.action(items))
            next_section = len(DOMAIN_SECTIONS)
            continue
        if keyword not in DOMAIN_SECTIONS[next_section:]:
            raise Unsupported  # an unknown section, or one out of the grammar's order
        next_section = DOMAIN_SECTIONS.index(keyword) + 1
        if keyword == ":requirements":
            reader.requirements = _requirements(items)
        elif keyword == ":types":
            reader.read_types(items)
        elif keyword == ":constants":
            constants = reader.typed(items, read_name)
            for _, types in constants:
                reader.check_type_known(types)
            reader.constants = tuple((constant, type_tags(types)) for constant, types in constants)
            reader.constant_names = {constant.lower(): constant for constant, _ in constants}
        else:
            reader.read_predicates(items)
    if len({action.name.lower() for action in actions}) != len(actions):
        raise Unsupported  # two actions of one name: the package's order between them is its set's
    return DomainSyntax(name, reader.types, reader.predicates, reader.constants, tuple(actions))


def _problem(expression: list[Expression]) -> ProblemSyntax:
    if len(expression) < 5 or expression[0] != "define":
        raise Unsupported
    name = read_header(expression[1], "problem")
    keyword, items = read_section(expression[2])
    if keyword != ":domain" or len(items) != 1:
        raise Unsupported
    domain_name = read_name(items[0])
    sections = expression[3:]
    keyword, items = read_section(sections[0])
    if keyword == ":requirements":
        _requirements(items)
        sections = sections[1:]
    objects: list[tuple[str, tuple[str, ...] | None]] = []
    if sections:
        keyword, items = read_section(sections[0])
        if keyword == ":objects":
            objects = read_typed_list(items, read_name)
            sections = sections[1:]
    if len(sections) != 2:
        raise Unsupported  # :init and :goal, and nothing after them (a :metric is left to the package)
    init = _init(sections[0], {name.lower(): name for name, _ in objects})
    keyword, items = read_section(sections[1])
    if keyword != ":goal" or len(items) != 1:
        raise Unsupported
    goal: list[SyntaxLiteral] = []
    _DomainReader(check_constants=False).condition(items[0], goal)  # no :equality, so an '=' is refused
    return ProblemSyntax(name, domain_name, tuple((o, type_tags(t)) for o, t in objects), init, tuple(goal))


def _init(section: Expression, objects: dict[str, str]) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """The positive facts of ``(:init ...)``; each fact names objects only, spelled as ``objects``
    (by lowercase name) declares them, as the package spells them."""
    keyword, items = read_section(section)
    if keyword != ":init":
        raise Unsupported
    facts: list[tuple[str, tuple[str, ...]]] = []
    for item in items:
        positive = True
        if isinstance(item, list) and item and item[0] == "not":
            if len(item) != 2:
                raise Unsupported
            positive, item = False, item[1]
        if not isinstance(item, list) or not item:
            raise Unsupported
        arguments = (read_name(argument) for argument in item[1:])
        fact = (read_name(item[0]), tuple(objects.get(argument.lower(), argument) for argument in arguments))
        if positive:
            facts.append(fact)
    return tuple(facts)
