"""Lifted action schemas and the problem's facts, translated from the ``pddl`` package's objects.

This is where the STRIPS fragment we support is enforced (typing, constants,
negative preconditions, equality, conjunctive goals with negated literals) and
where names are checked against their declarations: an undeclared predicate,
object, type or variable becomes a ``PlanningInputError`` that names it and the
line it is on. PDDL names are case-insensitive; we keep the spelling of the
declaration.
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


def _object_types(term: Term) -> frozenset[str]:
    return frozenset(str(t) for t in term.type_tags) or frozenset({ROOT_TYPE})


class _Translator:
    def __init__(self, domain: Domain, problem: Problem, dsrc: PddlSource, psrc: PddlSource) -> None:
        self.domain, self.problem, self.dsrc, self.psrc = domain, problem, dsrc, psrc
        declared_types = {str(k): (str(v) if v is not None else None) for k, v in domain.types.items()}
        self.type_names = _Names([*declared_types, ROOT_TYPE])
        self.ancestors = _type_ancestors(declared_types)
        self.predicates = {str(p.name): p.arity for p in domain.predicates}
        self.predicate_names = _Names(self.predicates)
        self.objects: dict[str, str] = {}
        self.objects_by_type: dict[str, list[str]] = {}
        for term, src in [(c, dsrc) for c in domain.constants] + [(o, psrc) for o in problem.objects]:
            self._declare_object(term, src)
        self.object_names = _Names(self.objects)

    def _declare_object(self, term: Term, src: PddlSource) -> None:
        name = str(term.name)
        types = _object_types(term)
        for type_name in types:
            if self.type_names.get(type_name) is None:
                raise src.error(f"object '{name}' has undeclared type '{type_name}'", type_name)
        spelled = sorted(self.type_names.get(t) or t for t in types)
        self.objects[name] = spelled[0]
        for type_name in spelled:
            for ancestor in self.ancestors.get(type_name, frozenset({type_name, ROOT_TYPE})):
                self.objects_by_type.setdefault(ancestor, []).append(name)

    def candidates(self, type_tags: frozenset[str], action: str, variable: str) -> tuple[str, ...]:
        allowed: set[str] = set()
        for type_name in type_tags:
            spelled = self.type_names.get(type_name)
            if spelled is None:
                raise self.dsrc.error(
                    f"action '{action}': parameter ?{variable} has undeclared type '{type_name}'",
                    type_name, after=action)
            allowed.update(self.objects_by_type.get(spelled, ()))
        return tuple(sorted(allowed))

    # -- lifted formulas -------------------------------------------------------------

    def predicate(self, atom: Predicate, where: str, src: PddlSource, after: str | None) -> str:
        name = self.predicate_names.get(str(atom.name))
        if name is None:
            raise src.error(f"{where} uses undefined predicate '{atom.name}'", str(atom.name), after)
        if self.predicates[name] != atom.arity:
            raise src.error(
                f"{where}: predicate '{name}' takes {self.predicates[name]} arguments, "
                f"got {atom.arity}", str(atom.name), after)
        return name

    def term(self, term: Term, parameters: set[str], where: str, src: PddlSource,
             after: str | None) -> str:
        if isinstance(term, Variable):
            if str(term.name) not in parameters:
                raise src.error(f"{where} uses undeclared variable '?{term.name}'",
                                "?" + str(term.name), after)
            return "?" + str(term.name)
        name = self.object_names.get(str(term.name))
        if name is None:
            raise src.error(f"{where} uses undeclared object '{term.name}'", str(term.name), after)
        return name

    def literals(self, formula: Formula | None, parameters: set[str], where: str,
                 src: PddlSource, after: str | None) -> list[tuple[bool, Formula]]:
        """Flatten a conjunction of literals into (positive, atom) pairs."""
        if formula is None:
            return []
        if isinstance(formula, And):
            out: list[tuple[bool, Formula]] = []
            for operand in formula.operands:
                out.extend(self.literals(operand, parameters, where, src, after))
            return out
        if isinstance(formula, Not) and isinstance(formula.argument, Predicate | EqualTo):
            return [(False, formula.argument)]
        if isinstance(formula, Predicate | EqualTo):
            return [(True, formula)]
        kind = type(formula).__name__
        raise src.error(
            f"{where}: '{kind}' is not supported (STRIPS conjunctions of literals, "
            "negative literals and equality only)", after)

    def lifted(self, atom: Formula, parameters: set[str], where: str, src: PddlSource,
               after: str | None) -> Literal | tuple[str, str]:
        if isinstance(atom, EqualTo):
            return (self.term(atom.left, parameters, where, src, after),
                    self.term(atom.right, parameters, where, src, after))
        assert isinstance(atom, Predicate)
        name = self.predicate(atom, where, src, after)
        return name, tuple(self.term(t, parameters, where, src, after) for t in atom.terms)

    def schema(self, action: object) -> ActionSchema:
        name = str(action.name)  # type: ignore[attr-defined]
        params: list[Variable] = list(action.parameters)  # type: ignore[attr-defined]
        param_names = [str(v.name) for v in params]
        where = f"action '{name}'"
        after = f":action {name}"
        if len(set(param_names)) != len(param_names):
            raise self.dsrc.error(f"{where} declares a parameter twice", name, after)
        scope = set(param_names)
        pre: list[Literal] = []
        pre_neg: list[Literal] = []
        equal: list[tuple[str, str]] = []
        not_equal: list[tuple[str, str]] = []
        for positive, atom in self.literals(action.precondition, scope, where, self.dsrc, after):  # type: ignore[attr-defined]
            lifted = self.lifted(atom, scope, where, self.dsrc, after)
            if isinstance(atom, EqualTo):
                (equal if positive else not_equal).append(lifted)  # type: ignore[arg-type]
            else:
                (pre if positive else pre_neg).append(lifted)  # type: ignore[arg-type]
        add: list[Literal] = []
        delete: list[Literal] = []
        for positive, atom in self.literals(action.effect, scope, where, self.dsrc, after):  # type: ignore[attr-defined]
            if isinstance(atom, EqualTo):
                raise self.dsrc.error(f"{where}: an effect cannot be an equality", name, after)
            lifted = self.lifted(atom, scope, where, self.dsrc, after)
            (add if positive else delete).append(lifted)  # type: ignore[arg-type]
        candidates = tuple(
            self.candidates(frozenset(str(t) for t in v.type_tags) or frozenset({ROOT_TYPE}),
                            name, str(v.name))
            for v in params)
        return ActionSchema(name, tuple("?" + p for p in param_names), candidates, tuple(pre),
                            tuple(pre_neg), tuple(equal), tuple(not_equal), tuple(add), tuple(delete))

    def ground_atom(self, atom: Formula, where: str, after: str) -> Atom:
        if not isinstance(atom, Predicate):
            raise self.psrc.error(f"{where}: only atoms are allowed here, not '{atom}'", after)
        name = self.predicate(atom, where, self.psrc, after)
        args = tuple(self.term(t, set(), where, self.psrc, after) for t in atom.terms)
        return (name, *args)

    def facts(self) -> tuple[frozenset[Atom], frozenset[Atom], frozenset[Atom]]:
        init: set[Atom] = set()
        for fact in self.problem.init:
            if isinstance(fact, Not):
                continue  # closed world: negative facts are implied
            init.add(self.ground_atom(fact, "problem :init", ":init"))
        goal: set[Atom] = set()
        goal_neg: set[Atom] = set()
        for positive, atom in self.literals(self.problem.goal, set(), "problem :goal",
                                            self.psrc, ":goal"):
            if isinstance(atom, EqualTo):
                raise self.psrc.error("problem :goal: equality is not supported in goals", ":goal")
            (goal if positive else goal_neg).add(self.ground_atom(atom, "problem :goal", ":goal"))
        return frozenset(init), frozenset(goal), frozenset(goal_neg)


def translate(domain: Domain, problem: Problem, dsrc: PddlSource, psrc: PddlSource) -> LiftedTask:
    """Check names and translate the parsed files into our lifted representation."""
    domain_name = str(domain.name)
    if str(problem.domain_name).lower() != domain_name.lower():
        raise psrc.error(
            f"problem is for domain '{problem.domain_name}' but the domain file "
            f"{dsrc.path} defines '{domain_name}'", str(problem.domain_name), ":domain")
    translator = _Translator(domain, problem, dsrc, psrc)
    # Keep the schemas in file order so that grounding (and so search) is deterministic.
    actions = sorted(domain.actions, key=lambda a: (dsrc.locate(str(a.name), ":action")[0] or 0,
                                                    str(a.name)))
    schemas = tuple(translator.schema(action) for action in actions)
    init, goal, goal_neg = translator.facts()
    return LiftedTask(domain_name, str(problem.name), dict(translator.objects),
                      dict(translator.predicates), schemas, init, goal, goal_neg)
