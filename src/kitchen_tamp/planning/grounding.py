"""Grounding a lifted task into a STRIPS ``Task``, pruned by relaxed reachability.

Ground actions are only built for parameter bindings whose positive
preconditions can all become true when delete effects are ignored. Bindings are
found by joining each schema's preconditions against the facts reached so far
(a small Datalog fixpoint), so a problem with dozens of objects grounds the few
hundred actions it can use instead of every type-correct combination.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from itertools import product
from pathlib import Path

from kitchen_tamp.planning.pddl_files import parse_domain, parse_problem, resolve_problem_path
from kitchen_tamp.planning.schemas import ActionSchema, LiftedTask, Literal, translate
from kitchen_tamp.planning.task import Atom, GroundAction, Task, mask_of

Binding = dict[str, str]


def _resolve(term: str, binding: Mapping[str, str]) -> str | None:
    return binding.get(term) if term.startswith("?") else term


def _instantiate(literal: Literal, binding: Mapping[str, str]) -> Atom:
    predicate, terms = literal
    return (predicate, *(binding[t] if t.startswith("?") else t for t in terms))


class _Grounder:
    def __init__(self, lifted: LiftedTask) -> None:
        self.lifted = lifted
        self.fluent = {pred for s in lifted.schemas for pred, _ in (*s.add, *s.delete)}
        self.facts: dict[str, set[tuple[str, ...]]] = {p: set() for p in lifted.predicates}
        for atom in lifted.init:
            self.facts[atom[0]].add(atom[1:])
        self.allowed = [
            {param: frozenset(cands) for param, cands in zip(s.parameters, s.candidates, strict=True)}
            for s in lifted.schemas
        ]

    def _consistent(self, schema: ActionSchema, binding: Binding) -> bool:
        for left, right in schema.equal:
            a, b = _resolve(left, binding), _resolve(right, binding)
            if a is not None and b is not None and a != b:
                return False
        for left, right in schema.not_equal:
            a, b = _resolve(left, binding), _resolve(right, binding)
            if a is not None and b is not None and a == b:
                return False
        return True

    def _match(self, terms: tuple[str, ...], args: tuple[str, ...], binding: Binding,
               allowed: Mapping[str, frozenset[str]]) -> Binding | None:
        extended: Binding | None = None
        for term, arg in zip(terms, args, strict=True):
            if term.startswith("?"):
                bound = binding.get(term) if extended is None else extended.get(term)
                if bound is None:
                    if arg not in allowed[term]:
                        return None
                    if extended is None:
                        extended = dict(binding)
                    extended[term] = arg
                elif bound != arg:
                    return None
            elif term != arg:
                return None
        return extended if extended is not None else binding

    def _bindings(self, index: int, schema: ActionSchema) -> Iterator[Binding]:
        allowed = self.allowed[index]
        # Most selective preconditions first: fewest matching facts.
        order = sorted(schema.pre, key=lambda lit: len(self.facts[lit[0]]))

        def join(i: int, binding: Binding) -> Iterator[Binding]:
            if i == len(order):
                yield binding
                return
            predicate, terms = order[i]
            for args in self.facts[predicate]:
                extended = self._match(terms, args, binding, allowed)
                if extended is not None and self._consistent(schema, extended):
                    yield from join(i + 1, extended)

        for partial in join(0, {}):
            free = [p for p in schema.parameters if p not in partial]
            for values in product(*(sorted(allowed[p]) for p in free)):
                binding = dict(partial)
                binding.update(zip(free, values, strict=True))
                if self._consistent(schema, binding) and self._static_negatives_hold(schema, binding):
                    yield binding

    def _static_negatives_hold(self, schema: ActionSchema, binding: Binding) -> bool:
        for predicate, terms in schema.pre_neg:
            if predicate not in self.fluent:
                args = tuple(binding[t] if t.startswith("?") else t for t in terms)
                if args in self.facts[predicate]:
                    return False
        return True

    def reachable_actions(self) -> dict[tuple[int, tuple[str, ...]], Binding]:
        """All relaxed-reachable bindings, keyed by (schema index, argument tuple)."""
        found: dict[tuple[int, tuple[str, ...]], Binding] = {}
        changed = set(self.facts)
        first_round = True
        while changed:
            new_facts: set[str] = set()
            for index, schema in enumerate(self.lifted.schemas):
                if not first_round and not any(p in changed for p, _ in schema.pre):
                    continue
                for binding in list(self._bindings(index, schema)):
                    key = (index, tuple(binding[p] for p in schema.parameters))
                    if key in found:
                        continue
                    found[key] = binding
                    for literal in schema.add:
                        atom = _instantiate(literal, binding)
                        if atom[1:] not in self.facts[atom[0]]:
                            self.facts[atom[0]].add(atom[1:])
                            new_facts.add(atom[0])
            changed = new_facts
            first_round = False
        return found


def ground(lifted: LiftedTask) -> Task:
    """Ground a lifted task, keeping only relaxed-reachable actions and fluent atoms."""
    grounder = _Grounder(lifted)
    bindings = grounder.reachable_actions()
    fluent = grounder.fluent
    reachable = sorted((p, *args) for p, rows in grounder.facts.items() if p in fluent for args in rows)
    ids = {atom: i for i, atom in enumerate(reachable)}

    actions: list[GroundAction] = []
    for (index, args), binding in sorted(bindings.items()):
        schema = lifted.schemas[index]
        pre = [ids[a] for a in (_instantiate(lit, binding) for lit in schema.pre) if a[0] in fluent]
        pre_neg = [ids[a] for a in (_instantiate(lit, binding) for lit in schema.pre_neg) if a in ids]
        add = sorted({ids[_instantiate(lit, binding)] for lit in schema.add})
        delete = [ids[a] for a in (_instantiate(lit, binding) for lit in schema.delete) if a in ids]
        pre_mask, neg_mask = mask_of(pre), mask_of(pre_neg)
        if pre_mask & neg_mask:
            continue  # contradictory precondition: never applicable
        actions.append(GroundAction(
            name=schema.name, args=args, pre=pre_mask, pre_neg=neg_mask, add=mask_of(add),
            delete=mask_of(delete), pre_ids=tuple(sorted(set(pre))), add_ids=tuple(add)))

    unreachable = {a for a in lifted.goal if (a not in ids if a[0] in fluent else a not in lifted.init)}
    unreachable |= {a for a in lifted.goal_neg if a[0] not in fluent and a in lifted.init}
    return Task(
        name=lifted.problem_name,
        domain_name=lifted.domain_name,
        objects=lifted.objects,
        init_atoms=lifted.init,
        goal_atoms=lifted.goal,
        negative_goal_atoms=lifted.goal_neg,
        atoms=tuple(reachable),
        initial_state=mask_of(ids[a] for a in lifted.init if a in ids),
        goal=mask_of(ids[a] for a in lifted.goal if a in ids),
        goal_neg=mask_of(ids[a] for a in lifted.goal_neg if a in ids),
        actions=tuple(actions),
        unreachable_goal_atoms=frozenset(unreachable),
    )


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
    domain, dsrc = parse_domain(domain_file)
    return ground(translate(domain, problem, dsrc, psrc))
