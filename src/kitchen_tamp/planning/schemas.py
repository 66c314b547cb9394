"""Lifted action schemas and the problem's facts, translated from the ``pddl`` package's objects.

This is where the STRIPS fragment we support is enforced (typing, constants,
negative preconditions, equality, conjunctive goals with negated literals) and
where names are checked against their declarations: an undeclared predicate,
object, type or variable becomes a ``PlanningInputError`` that names it and the
line it is on. PDDL names are case-insensitive; we keep the spelling of the
declaration.

The work is split in two: ``DomainModel`` checks and translates what depends on
the domain alone (types, predicates, constants, action schemas), so a domain
used for many problems is translated once; ``translate_problem`` adds a
problem's objects, facts and goal.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from pddl.core import Domain, Problem
from pddl.logic.base import And, Formula, Not
from pddl.logic.predicates import EqualTo, Predicate
from pddl.logic.terms import Term, Variable

from kitchen_tamp.planning.pddl_files import PddlSource
from kitchen_tamp.planning.task import Atom

ROOT_TYPE = "object"

Literal = tuple[str, tuple[str, ...]]
"""A lifted atom (predicate, terms); a term starting with ``?`` is a variable."""


@dataclass(frozen=True)
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


@dataclass(frozen=True)
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


def _type_tags(term: Term) -> frozenset[str]:
    return frozenset(str(t) for t in term.type_tags) or frozenset({ROOT_TYPE})


def _flatten(formula: Formula | None, where: str, src: PddlSource,
             after: str | None) -> list[tuple[bool, Formula]]:
    """Flatten a conjunction of literals into (positive, atom) pairs."""
    if formula is None:
        return []
    if isinstance(formula, And):
        out: list[tuple[bool, Formula]] = []
        for operand in formula.operands:
            out.extend(_flatten(operand, where, src, after))
        return out
    if isinstance(formula, Not) and isinstance(formula.argument, Predicate | EqualTo):
        return [(False, formula.argument)]
    if isinstance(formula, Predicate | EqualTo):
        return [(True, formula)]
    kind = type(formula).__name__
    raise src.error(
        f"{where}: '{kind}' is not supported (STRIPS conjunctions of literals, "
        "negative literals and equality only)", after)


@dataclass(frozen=True)
class _LiftedAction:
    """An action schema before a problem tells which objects its parameters may take."""

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

    def __init__(self, domain: Domain, source: PddlSource) -> None:
        self.name = str(domain.name)
        self.source = source
        declared = {str(k): (str(v) if v is not None else None) for k, v in domain.types.items()}
        self.type_names = _Names([*declared, ROOT_TYPE])
        self.ancestors = _type_ancestors(declared)
        self.predicates = {str(p.name): p.arity for p in domain.predicates}
        self.predicate_names = _Names(self.predicates)
        self.constants = tuple(sorted(
            (str(c.name), self.spelled_types(_type_tags(c), str(c.name), source)) for c in domain.constants))
        self.constant_names = _Names(name for name, _ in self.constants)
        # File order, so that grounding (and so search) is deterministic.
        actions = sorted(domain.actions, key=lambda a: (source.locate(str(a.name), ":action")[0] or 0,
                                                        str(a.name)))
        self.actions = tuple(self._action(action) for action in actions)

    def spelled_types(self, tags: frozenset[str], name: str, src: PddlSource) -> tuple[str, ...]:
        """The declared spelling of an object's types; an undeclared type is an input error."""
        spelled = []
        for type_name in tags:
            declared = self.type_names.get(type_name)
            if declared is None:
                raise src.error(f"object '{name}' has undeclared type '{type_name}'", type_name)
            spelled.append(declared)
        return tuple(sorted(spelled))

    def predicate(self, atom: Predicate, where: str, src: PddlSource, after: str | None) -> str:
        """The declared predicate name of ``atom``, checked for existence and arity."""
        name = self.predicate_names.get(str(atom.name))
        if name is None:
            raise src.error(f"{where} uses undefined predicate '{atom.name}'", str(atom.name), after)
        if self.predicates[name] != atom.arity:
            raise src.error(
                f"{where}: predicate '{name}' takes {self.predicates[name]} arguments, "
                f"got {atom.arity}", str(atom.name), after)
        return name

    def _term(self, term: Term, parameters: set[str], where: str, after: str) -> str:
        if isinstance(term, Variable):
            if str(term.name) not in parameters:
                raise self.source.error(f"{where} uses undeclared variable '?{term.name}'",
                                        "?" + str(term.name), after)
            return "?" + str(term.name)
        name = self.constant_names.get(str(term.name))
        if name is None:
            raise self.source.error(f"{where} uses undeclared object '{term.name}'", str(term.name), after)
        return name

    def _lifted(self, atom: Formula, scope: set[str], where: str, after: str) -> Literal | tuple[str, str]:
        if isinstance(atom, EqualTo):
            return (self._term(atom.left, scope, where, after), self._term(atom.right, scope, where, after))
        assert isinstance(atom, Predicate)
        name = self.predicate(atom, where, self.source, after)
        return name, tuple(self._term(t, scope, where, after) for t in atom.terms)

    def _action(self, action: object) -> _LiftedAction:
        name = str(action.name)  # type: ignore[attr-defined]
        params: list[Variable] = list(action.parameters)  # type: ignore[attr-defined]
        param_names = [str(v.name) for v in params]
        where = f"action '{name}'"
        after = f":action {name}"
        if len(set(param_names)) != len(param_names):
            raise self.source.error(f"{where} declares a parameter twice", name, after)
        scope = set(param_names)
        pre: list[Literal] = []
        pre_neg: list[Literal] = []
        equal: list[tuple[str, str]] = []
        not_equal: list[tuple[str, str]] = []
        for positive, atom in _flatten(action.precondition, where, self.source, after):  # type: ignore[attr-defined]
            lifted = self._lifted(atom, scope, where, after)
            if isinstance(atom, EqualTo):
                (equal if positive else not_equal).append(lifted)  # type: ignore[arg-type]
            else:
                (pre if positive else pre_neg).append(lifted)  # type: ignore[arg-type]
        add: list[Literal] = []
        delete: list[Literal] = []
        for positive, atom in _flatten(action.effect, where, self.source, after):  # type: ignore[attr-defined]
            if isinstance(atom, EqualTo):
                raise self.source.error(f"{where}: an effect cannot be an equality", name, after)
            lifted = self._lifted(atom, scope, where, after)
            (add if positive else delete).append(lifted)  # type: ignore[arg-type]
        types = []
        for variable in params:
            tags = _type_tags(variable)
            for type_name in tags:
                if self.type_names.get(type_name) is None:
                    raise self.source.error(
                        f"{where}: parameter ?{variable.name} has undeclared type '{type_name}'",
                        type_name, after=name)
            types.append(frozenset(self.type_names.get(t) or t for t in tags))
        return _LiftedAction(name, tuple("?" + p for p in param_names), tuple(types), tuple(pre),
                             tuple(pre_neg), tuple(equal), tuple(not_equal), tuple(add), tuple(delete))


class _ProblemTranslator:
    def __init__(self, model: DomainModel, problem: Problem, psrc: PddlSource) -> None:
        self.model, self.problem, self.psrc = model, problem, psrc
        self.objects: dict[str, str] = {}
        self.objects_by_type: dict[str, list[str]] = {}
        for name, types in model.constants:
            self._declare(name, types)
        for term in problem.objects:
            name = str(term.name)
            self._declare(name, model.spelled_types(_type_tags(term), name, psrc))
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

    def ground_atom(self, atom: Formula, where: str, after: str) -> Atom:
        if not isinstance(atom, Predicate):
            raise self.psrc.error(f"{where}: only atoms are allowed here, not '{atom}'", after)
        name = self.model.predicate(atom, where, self.psrc, after)
        args = []
        for term in atom.terms:
            if isinstance(term, Variable):
                raise self.psrc.error(f"{where} uses undeclared variable '?{term.name}'",
                                      "?" + str(term.name), after)
            declared = self.object_names.get(str(term.name))
            if declared is None:
                raise self.psrc.error(f"{where} uses undeclared object '{term.name}'", str(term.name), after)
            args.append(declared)
        return (name, *args)

    def facts(self) -> tuple[frozenset[Atom], frozenset[Atom], frozenset[Atom]]:
        init: set[Atom] = set()
        for fact in self.problem.init:
            if isinstance(fact, Not):
                continue  # closed world: negative facts are implied
            init.add(self.ground_atom(fact, "problem :init", ":init"))
        goal: set[Atom] = set()
        goal_neg: set[Atom] = set()
        for positive, atom in _flatten(self.problem.goal, "problem :goal", self.psrc, ":goal"):
            if isinstance(atom, EqualTo):
                raise self.psrc.error("problem :goal: equality is not supported in goals", ":goal")
            (goal if positive else goal_neg).add(self.ground_atom(atom, "problem :goal", ":goal"))
        return frozenset(init), frozenset(goal), frozenset(goal_neg)


def translate_problem(model: DomainModel, problem: Problem, psrc: PddlSource) -> LiftedTask:
    """Check a problem's names against its domain and translate both into a ``LiftedTask``."""
    if str(problem.domain_name).lower() != model.name.lower():
        raise psrc.error(
            f"problem is for domain '{problem.domain_name}' but the domain file "
            f"{model.source.path} defines '{model.name}'", str(problem.domain_name), ":domain")
    translator = _ProblemTranslator(model, problem, psrc)
    schemas = tuple(translator.schema(action) for action in model.actions)
    init, goal, goal_neg = translator.facts()
    return LiftedTask(model.name, str(problem.name), dict(translator.objects),
                      dict(model.predicates), schemas, init, goal, goal_neg)


def translate(domain: Domain, problem: Problem, dsrc: PddlSource, psrc: PddlSource) -> LiftedTask:
    """Check names and translate the parsed files into our lifted representation."""
    return translate_problem(DomainModel(domain, dsrc), problem, psrc)
