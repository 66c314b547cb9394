"""Lifted action schemas and the problem's facts, checked and translated from ``reading.syntax`` records.

This is where the STRIPS fragment we support is enforced (typing, constants,
negative preconditions, equality, conjunctive goals with negated literals) and
where names are checked against their declarations: an undeclared predicate,
object, type or variable becomes a ``PlanningInputError`` that names it and the
line it is on. PDDL names are case-insensitive; we keep the spelling of the
declaration. The records come from either reader (``strips_text_reader`` or
the ``pddl`` package through ``reading.package_reader``); what is checked here does not
depend on which.

The work is split in two: ``DomainModel`` checks and translates what depends on
the domain alone (types, predicates, constants, action schemas), so a domain
used for many problems is translated once; ``translate_problem`` adds a
problem's objects, facts and goal.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

from kitchen_tamp.planning.reading.syntax import EQUALITY, ROOT_TYPE

if TYPE_CHECKING:
    from kitchen_tamp.planning.reading.source import PddlSource
    from kitchen_tamp.planning.reading.syntax import ActionSyntax, DomainSyntax, ProblemSyntax, SyntaxLiteral
    from kitchen_tamp.planning.task import Atom

Literal = tuple[str, tuple[str, ...]]
"""A lifted atom (predicate, terms); a term starting with ``?`` is a variable."""


@dataclass(frozen=True, slots=True)
class ActionSchema:
    """A lifted STRIPS action.

    ``candidates[i]`` lists the objects parameter ``i`` may take (its type,
    including subtypes and ``either``). ``equal`` and ``not_equal`` hold pairs of
    terms that must (not) be the same object.
    """

    name: str
    parameters: tuple[str, ...]
    candidates: tuple[tuple[str, ...], ...]
    pre: tuple[Literal, ...]
    pre_neg: tuple[Literal, ...]
    equal: tuple[tuple[str, str], ...]
    not_equal: tuple[tuple[str, str], ...]
    add: tuple[Literal, ...]
    delete: tuple[Literal, ...]


@dataclass(frozen=True, slots=True)
class LiftedTask:
    """Everything grounding needs, with names checked and spelled as declared."""

    domain_name: str
    problem_name: str
    objects: Mapping[str, str]
    predicates: Mapping[str, int]
    schemas: tuple[ActionSchema, ...]
    init: frozenset[Atom]
    goal: frozenset[Atom]
    goal_neg: frozenset[Atom]


class _Names:
    """Case-insensitive lookup of declared names, keeping the declared spelling."""

    def __init__(self, names: Iterable[str]) -> None:
        self.by_lower = {name.lower(): name for name in names}

    def get(self, name: str) -> str | None:
        return self.by_lower.get(name.lower())


def _type_ancestors(types: Mapping[str, str | None]) -> dict[str, frozenset[str]]:
    """Each declared type with itself and all its ancestors, ``object`` included."""
    result: dict[str, frozenset[str]] = {}
    for start in [*types, ROOT_TYPE]:
        chain = {start, ROOT_TYPE}
        current: str | None = types.get(start)
        while current is not None and current not in chain:
            chain.add(current)
            current = types.get(current)
        result[start] = frozenset(chain)
    return result


class _LiftedAction(NamedTuple):
    """An action schema before a problem tells which objects its parameters may take.

    A named tuple, not a frozen dataclass: creating a dataclass costs about a millisecond of every
    planner process's start, and this record is private to the module."""

    name: str
    parameters: tuple[str, ...]
    parameter_types: tuple[frozenset[str], ...]
    pre: tuple[Literal, ...]
    pre_neg: tuple[Literal, ...]
    equal: tuple[tuple[str, str], ...]
    not_equal: tuple[tuple[str, str], ...]
    add: tuple[Literal, ...]
    delete: tuple[Literal, ...]


class DomainModel:
    """A domain's declarations and action schemas, checked; shared by all its problems."""

    def __init__(self, domain: DomainSyntax, source: PddlSource) -> None:
        self.name = domain.name
        self.source = source
        self.type_names = _Names([*domain.types, ROOT_TYPE])
        self.ancestors = _type_ancestors(domain.types)
        self.predicates = dict(domain.predicates)
        self.predicate_names = _Names(self.predicates)
        self.constants = tuple(sorted(
            (name, self.spelled_types(tags, name, source)) for name, tags in domain.constants))
        self.constant_names = _Names(name for name, _ in self.constants)
        self.actions = tuple(self._action(action) for action in domain.actions)

    def spelled_types(self, tags: frozenset[str], name: str, src: PddlSource) -> tuple[str, ...]:
        """The declared spelling of an object's types; an undeclared type is an input error."""
        spelled = []
        for type_name in tags:
            declared = self.type_names.get(type_name)
            if declared is None:
                raise src.error(f"object '{name}' has undeclared type '{type_name}'", type_name)
            spelled.append(declared)
        return tuple(sorted(spelled))

    def predicate(self, atom: str, arity: int, where: str, src: PddlSource, after: str | None) -> str:
        """The declared predicate name of ``atom``, checked for existence and arity."""
        name = self.predicate_names.get(atom)
        if name is None:
            raise src.error(f"{where} uses undefined predicate '{atom}'", atom, after)
        if self.predicates[name] != arity:
            raise src.error(
                f"{where}: predicate '{name}' takes {self.predicates[name]} arguments, "
                f"got {arity}", atom, after)
        return name

    def _term(self, term: str, parameters: set[str], where: str, after: str) -> str:
        if term.startswith("?"):
            if term[1:] not in parameters:
                raise self.source.error(f"{where} uses undeclared variable '{term}'", term, after)
            return term
        name = self.constant_names.get(term)
        if name is None:
            raise self.source.error(f"{where} uses undeclared object '{term}'", term, after)
        return name

    def _lifted(self, literal: SyntaxLiteral, scope: set[str], where: str, after: str) -> Literal:
        _, predicate, terms = literal
        if predicate != EQUALITY:
            predicate = self.predicate(predicate, len(terms), where, self.source, after)
        return predicate, tuple(self._term(t, scope, where, after) for t in terms)

    def _action(self, action: ActionSyntax) -> _LiftedAction:
        name = action.name
        param_names = [variable for variable, _ in action.parameters]
        where = f"action '{name}'"
        after = f":action {name}"
        if len(set(param_names)) != len(param_names):
            raise self.source.error(f"{where} declares a parameter twice", name, after)
        scope = set(param_names)
        pre: list[Literal] = []
        pre_neg: list[Literal] = []
        equal: list[tuple[str, str]] = []
        not_equal: list[tuple[str, str]] = []
        for literal in action.precondition:
            predicate, terms = self._lifted(literal, scope, where, after)
            if predicate == EQUALITY:
                (equal if literal[0] else not_equal).append((terms[0], terms[1]))
            else:
                (pre if literal[0] else pre_neg).append((predicate, terms))
        add: list[Literal] = []
        delete: list[Literal] = []
        for literal in action.effect:
            if literal[1] == EQUALITY:
                raise self.source.error(f"{where}: an effect cannot be an equality", name, after)
            (add if literal[0] else delete).append(self._lifted(literal, scope, where, after))
        types = []
        for variable, tags in action.parameters:
            for type_name in tags:
                if self.type_names.get(type_name) is None:
                    raise self.source.error(
                        f"{where}: parameter ?{variable} has undeclared type '{type_name}'",
                        type_name, after=name)
            types.append(frozenset(self.type_names.get(t) or t for t in tags))
        # A literal written twice counts once (the pddl package's conjunctions drop repeats too).
        return _LiftedAction(name, tuple("?" + p for p in param_names), tuple(types), *(
            tuple(dict.fromkeys(part)) for part in (pre, pre_neg, equal, not_equal, add, delete)))  # type: ignore[arg-type]


class _ProblemTranslator:
    def __init__(self, model: DomainModel, problem: ProblemSyntax, psrc: PddlSource) -> None:
        self.model, self.problem, self.psrc = model, problem, psrc
        self.objects: dict[str, str] = {}
        self.objects_by_type: dict[str, list[str]] = {}
        for name, types in model.constants:
            self._declare(name, types)
        for name, tags in problem.objects:
            self._declare(name, model.spelled_types(tags, name, psrc))
        self.object_names = _Names(self.objects)

    def _declare(self, name: str, types: tuple[str, ...]) -> None:
        self.objects[name] = types[0]
        for type_name in types:
            for ancestor in self.model.ancestors.get(type_name, frozenset({type_name, ROOT_TYPE})):
                self.objects_by_type.setdefault(ancestor, []).append(name)

    def schema(self, action: _LiftedAction) -> ActionSchema:
        candidates = []
        for types in action.parameter_types:
            allowed: set[str] = set()
            for type_name in types:
                allowed.update(self.objects_by_type.get(type_name, ()))
            candidates.append(tuple(sorted(allowed)))
        return ActionSchema(action.name, action.parameters, tuple(candidates), action.pre,
                            action.pre_neg, action.equal, action.not_equal, action.add, action.delete)

    def ground_atom(self, predicate: str, terms: tuple[str, ...], where: str, after: str) -> Atom:
        name = self.model.predicate(predicate, len(terms), where, self.psrc, after)
        args = []
        for term in terms:
            if term.startswith("?"):
                raise self.psrc.error(f"{where} uses undeclared variable '{term}'", term, after)
            declared = self.object_names.get(term)
            if declared is None:
                raise self.psrc.error(f"{where} uses undeclared object '{term}'", term, after)
            args.append(declared)
        return (name, *args)

    def facts(self) -> tuple[frozenset[Atom], frozenset[Atom], frozenset[Atom]]:
        init = {self.ground_atom(predicate, terms, "problem :init", ":init")
                for predicate, terms in self.problem.init}
        goal: set[Atom] = set()
        goal_neg: set[Atom] = set()
        for positive, predicate, terms in self.problem.goal:
            (goal if positive else goal_neg).add(self.ground_atom(predicate, terms, "problem :goal", ":goal"))
        return frozenset(init), frozenset(goal), frozenset(goal_neg)


def translate_problem(model: DomainModel, problem: ProblemSyntax, psrc: PddlSource) -> LiftedTask:
    """Check a problem's names against its domain and translate both into a ``LiftedTask``."""
    if problem.domain_name.lower() != model.name.lower():
        raise psrc.error(
            f"problem is for domain '{problem.domain_name}' but the domain file "
            f"{model.source.path} defines '{model.name}'", problem.domain_name, ":domain")
    translator = _ProblemTranslator(model, problem, psrc)
    schemas = tuple(translator.schema(action) for action in model.actions)
    init, goal, goal_neg = translator.facts()
    return LiftedTask(model.name, problem.name, dict(translator.objects),
                      dict(model.predicates), schemas, init, goal, goal_neg)


def translate(domain: DomainSyntax, problem: ProblemSyntax, dsrc: PddlSource, psrc: PddlSource) -> LiftedTask:
    """Check names and translate the read files into our lifted representation."""
    return translate_problem(DomainModel(domain, dsrc), problem, psrc)
