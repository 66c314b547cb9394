"""Grounding a lifted task into a STRIPS ``Task``, pruned by relaxed reachability.

Ground actions are only built for parameter bindings whose positive
preconditions can all become true when delete effects are ignored. The
bindings are found by a semi-naive Datalog fixpoint: facts are processed one at
a time, and each new fact is joined, as the trigger, with the facts processed
before it for every precondition it can match. So every binding is found when
the last of its precondition facts is processed, and no join is repeated.

Each schema is compiled once per task: for each precondition taken as the
trigger, the other preconditions get a join order (most bound arguments first),
an argument position to look facts up by, and the equality tests that become
decidable at each step. Atom ids are then read off with ``operator.itemgetter``
templates, so building a ground action is a few C calls per literal.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterator, Sequence
from itertools import product, repeat
from operator import itemgetter, or_
from typing import NamedTuple

from kitchen_tamp.planning.schemas import ActionSchema, LiftedTask
from kitchen_tamp.planning.task import GroundAction, Task, mask_of

Values = list[str]
"""A partial binding: one entry per parameter ("" while unbound), then the schema's constants.

Which slots are bound at each join step is known when the schema is compiled,
so the placeholder is never compared with an object name."""

Test = tuple[int, int, bool]
"""Slots ``a`` and ``b`` must hold the same object (True) or different objects (False)."""


class _Step(NamedTuple):
    """Matching one precondition literal against one fact's arguments (a named tuple, as ``_Trigger``).

    ``checks`` are (argument position, slot) pairs whose slot is already bound,
    ``assigns`` bind a slot for the first time, ``repeats`` compare with a slot
    bound earlier in this same literal; ``tests`` become decidable after it.
    ``lookup`` is the (position, slot) facts are looked up by, or None to scan.
    """

    predicate: str
    checks: tuple[tuple[int, int], ...]
    assigns: tuple[tuple[int, int], ...]
    repeats: tuple[tuple[int, int], ...]
    tests: tuple[Test, ...]
    lookup: tuple[int, int] | None


class _Trigger(NamedTuple):
    """How to complete a binding when a new fact matches precondition ``first``.

    Named tuples, not frozen dataclasses: creating a dataclass costs about a millisecond of every
    planner process's start, and these records are private to the module."""

    schema: int
    first: _Step
    rest: tuple[_Step, ...]
    final_tests: tuple[Test, ...]


class _CompiledSchema:
    """A schema with every term replaced by a slot number (parameters first, then constants)."""

    def __init__(self, schema: ActionSchema, fluent: set[str]) -> None:
        self.schema = schema
        n = len(schema.parameters)
        slot_of = {p: i for i, p in enumerate(schema.parameters)}
        constants: list[str] = []
        for _, terms in (*schema.pre, *schema.pre_neg, *schema.add, *schema.delete):
            constants.extend(t for t in terms if not t.startswith("?") and t not in slot_of)
        for pair in (*schema.equal, *schema.not_equal):
            constants.extend(t for t in pair if not t.startswith("?") and t not in slot_of)
        for constant in constants:
            slot_of.setdefault(constant, len(slot_of))
        self.n_parameters = n
        self.template: Values = [""] * n + list(dict.fromkeys(constants))
        self.allowed = [frozenset(c) for c in schema.candidates]
        self.pre = [(p, tuple(slot_of[t] for t in terms)) for p, terms in schema.pre]
        self.pre_neg = [(p, tuple(slot_of[t] for t in terms)) for p, terms in schema.pre_neg]
        self.add = [(p, tuple(slot_of[t] for t in terms)) for p, terms in schema.add]
        self.delete = [(p, tuple(slot_of[t] for t in terms)) for p, terms in schema.delete]
        tests = [(slot_of[a], slot_of[b], True) for a, b in schema.equal]
        tests += [(slot_of[a], slot_of[b], False) for a, b in schema.not_equal]
        # Tests between two constants are decided now.
        self.never = any((self.template[a] == self.template[b]) != same
                         for a, b, same in tests if a >= n and b >= n)
        self.tests = [(a, b, same) for a, b, same in tests if a < n or b < n]
        in_pre = {s for _, slots in self.pre for s in slots}
        self.free = tuple(s for s in range(n) if s not in in_pre)
        self.add_args = [(p, _tuple_getter(slots)) for p, slots in self.add]
        self.static_neg = [(p, _tuple_getter(slots)) for p, slots in self.pre_neg if p not in fluent]

    def _step(self, literal: tuple[str, tuple[int, ...]], bound: set[int],
              pending: list[Test], lookup: bool) -> _Step:
        predicate, slots = literal
        checks, assigns, repeats = [], [], []
        seen: set[int] = set()
        for position, slot in enumerate(slots):
            if slot in bound or slot >= self.n_parameters:
                checks.append((position, slot))
            elif slot in seen:
                repeats.append((position, slot))
            else:
                assigns.append((position, slot))
                seen.add(slot)
        bound |= seen
        decided = [t for t in pending if self._bound(t[0], bound) and self._bound(t[1], bound)]
        for test in decided:
            pending.remove(test)
        return _Step(predicate, tuple(checks), tuple(assigns), tuple(repeats), tuple(decided),
                     checks[0] if lookup and checks else None)

    def _bound(self, slot: int, bound: set[int]) -> bool:
        return slot >= self.n_parameters or slot in bound

    def triggers(self, index: int) -> list[_Trigger]:
        """One join plan per positive precondition, taking that precondition as the trigger."""
        plans = []
        for first_index, first in enumerate(self.pre):
            bound: set[int] = set()
            pending = list(self.tests)
            first_step = self._step(first, bound, pending, lookup=False)
            rest = [lit for i, lit in enumerate(self.pre) if i != first_index]
            steps = []
            while rest:
                # Most bound arguments first (a lookup, not a scan), then fewest new variables.
                best = min(rest, key=lambda lit: (
                    -sum(self._bound(s, bound) for s in lit[1]),
                    len({s for s in lit[1] if not self._bound(s, bound)})))
                rest.remove(best)
                steps.append(self._step(best, bound, pending, lookup=True))
            plans.append(_Trigger(index, first_step, tuple(steps), tuple(pending)))
        return plans


def _extend(values: Values, step: _Step, args: tuple[str, ...],
            allowed: Sequence[frozenset[str]]) -> Values | None:
    """``values`` extended by matching ``step``'s literal to ``args``, or None if they clash."""
    for position, slot in step.checks:
        if args[position] != values[slot]:
            return None
    extended = values.copy()
    for position, slot in step.assigns:
        arg = args[position]
        if arg not in allowed[slot]:
            return None
        extended[slot] = arg
    for position, slot in step.repeats:
        if args[position] != extended[slot]:
            return None
    for a, b, same in step.tests:
        if (extended[a] == extended[b]) != same:
            return None
    return extended


class _Grounder:
    def __init__(self, lifted: LiftedTask) -> None:
        self.lifted = lifted
        self.fluent = {pred for s in lifted.schemas for pred, _ in (*s.add, *s.delete)}
        self.schemas = [_CompiledSchema(s, self.fluent) for s in lifted.schemas]
        self.known: dict[str, set[tuple[str, ...]]] = {p: set() for p in lifted.predicates}
        self.processed: dict[str, list[tuple[str, ...]]] = {p: [] for p in lifted.predicates}
        self.triggers: dict[str, list[_Trigger]] = {p: [] for p in lifted.predicates}
        self.index: dict[tuple[str, int], dict[str, list[tuple[str, ...]]]] = {}
        for i, compiled in enumerate(self.schemas):
            if compiled.never:
                continue
            for trigger in compiled.triggers(i):
                self.triggers[trigger.first.predicate].append(trigger)
                for step in trigger.rest:
                    if step.lookup is not None:
                        self.index.setdefault((step.predicate, step.lookup[0]), {})
        self.index_positions: dict[str, list[tuple[int, dict[str, list[tuple[str, ...]]]]]] = {
            p: [] for p in lifted.predicates}
        for (predicate, position), table in self.index.items():
            self.index_positions[predicate].append((position, table))
        self.found: list[set[tuple[str, ...]]] = [set() for _ in self.schemas]
        self.queue: deque[tuple[str, tuple[str, ...]]] = deque()

    def _join(self, compiled: _CompiledSchema, steps: tuple[_Step, ...], i: int,
              values: Values) -> Iterator[Values]:
        if i == len(steps):
            yield values
            return
        step = steps[i]
        if step.lookup is None:
            rows: list[tuple[str, ...]] = self.processed[step.predicate]
        else:
            position, slot = step.lookup
            rows = self.index[step.predicate, position].get(values[slot], [])
        allowed = compiled.allowed
        for args in rows:
            extended = _extend(values, step, args, allowed)
            if extended is not None:
                yield from self._join(compiled, steps, i + 1, extended)

    def _record(self, index: int, compiled: _CompiledSchema, values: Values,
                final_tests: tuple[Test, ...]) -> None:
        for binding in (self._free_bindings(compiled, values) if compiled.free else (values,)):
            if final_tests and any((binding[a] == binding[b]) != same for a, b, same in final_tests):
                continue
            if compiled.static_neg and not self._static_negatives_hold(compiled, binding):
                continue
            key = tuple(binding[:compiled.n_parameters])
            found = self.found[index]
            if key in found:
                continue
            found.add(key)
            known, queue = self.known, self.queue
            for predicate, get in compiled.add_args:
                args = get(binding)
                rows = known[predicate]
                if args not in rows:
                    rows.add(args)
                    queue.append((predicate, args))

    def _free_bindings(self, compiled: _CompiledSchema, values: Values) -> Iterator[Values]:
        choices = [sorted(compiled.allowed[s]) for s in compiled.free]
        for chosen in product(*choices):
            binding = values.copy()
            for slot, value in zip(compiled.free, chosen, strict=True):
                binding[slot] = value
            yield binding

    def _static_negatives_hold(self, compiled: _CompiledSchema, binding: Values) -> bool:
        return not any(get(binding) in self.known[predicate] for predicate, get in compiled.static_neg)

    def reachable(self) -> list[set[tuple[str, ...]]]:
        """Every relaxed-reachable binding (as its argument tuple), per schema."""
        for atom in sorted(self.lifted.init):
            self.known[atom[0]].add(atom[1:])
            self.queue.append((atom[0], atom[1:]))
        for index, compiled in enumerate(self.schemas):
            if not compiled.pre and not compiled.never:
                self._record(index, compiled, compiled.template.copy(), tuple(compiled.tests))
        queue = self.queue
        while queue:
            predicate, args = queue.popleft()
            self.processed[predicate].append(args)
            for position, table in self.index_positions[predicate]:
                table.setdefault(args[position], []).append(args)
            for trigger in self.triggers[predicate]:
                compiled = self.schemas[trigger.schema]
                start = _extend(compiled.template, trigger.first, args, compiled.allowed)
                if start is None:
                    continue
                for values in self._join(compiled, trigger.rest, 0, start):
                    self._record(trigger.schema, compiled, values, trigger.final_tests)
        return self.found


Getter = Callable[[Sequence[str]], object]


def _getter(slots: tuple[int, ...]) -> Getter:
    """Reads a literal's key in an atom-id table from a binding: (), one name, or a tuple."""
    if not slots:
        return lambda _values: ()
    return itemgetter(*slots)


def _tuple_getter(slots: tuple[int, ...]) -> Callable[[Sequence[str]], tuple[str, ...]]:
    """Reads a literal's arguments from a binding, always as a tuple."""
    if len(slots) >= 2:
        return itemgetter(*slots)
    if slots:
        slot = slots[0]
        return lambda values: (values[slot],)
    return lambda _values: ()


def _masks(columns: list[list[int]], bit: list[int], count: int) -> list[int]:
    """Per binding, the bitset of the atoms in ``columns`` (one list of atom ids per literal).

    Column by column with ``map``, so the loops over bindings run in C.
    """
    if not columns:
        return [0] * count
    masks = list(map(bit.__getitem__, columns[0]))
    for column in columns[1:]:
        masks = list(map(or_, masks, map(bit.__getitem__, column)))
    return masks


def _sorted_ids(columns: list[list[int]], count: int) -> Iterator[tuple[int, ...]]:
    """Per binding, the distinct atom ids in ``columns``, sorted."""
    if not columns:
        return repeat((), count)
    return map(tuple, map(sorted, map(set, zip(*columns, strict=True))))


def _key(args: tuple[str, ...]) -> object:
    return args[0] if len(args) == 1 else args


def ground(lifted: LiftedTask) -> Task:
    """Ground a lifted task, keeping only relaxed-reachable actions and fluent atoms."""
    grounder = _Grounder(lifted)
    found = grounder.reachable()
    fluent = grounder.fluent
    reachable = sorted((p, *args) for p, rows in grounder.known.items() if p in fluent for args in rows)
    ids = {atom: i for i, atom in enumerate(reachable)}
    ids_by_key: dict[str, dict[object, int]] = {p: {} for p in lifted.predicates}
    for atom, i in ids.items():
        ids_by_key[atom[0]][_key(atom[1:])] = i

    def templates(literals: list[tuple[str, tuple[int, ...]]]) -> list[tuple[dict[object, int], Getter]]:
        return [(ids_by_key[p], _getter(slots)) for p, slots in literals if p in fluent]

    # bit[i] is atom i's mask; the extra 0 at the end is bit[-1], for "never reachable".
    bit = [1 << i for i in range(len(reachable))] + [0]
    actions: list[GroundAction] = []
    for index, compiled in enumerate(grounder.schemas):
        rows = sorted(found[index])
        constants = tuple(compiled.template[compiled.n_parameters:])
        values = [args + constants for args in rows] if constants else rows
        pre, pre_neg, add, delete = (
            [list(map(table.get, map(get, values), repeat(-1))) for table, get in templates(literals)]
            for literals in (compiled.pre, compiled.pre_neg, compiled.add, compiled.delete))
        pre_masks, neg_masks = _masks(pre, bit, len(rows)), _masks(pre_neg, bit, len(rows))
        add_masks, delete_masks = _masks(add, bit, len(rows)), _masks(delete, bit, len(rows))
        name = compiled.schema.name
        for args, pre_mask, neg_mask, add_mask, delete_mask, pre_ids, add_ids in zip(
                rows, pre_masks, neg_masks, add_masks, delete_masks, _sorted_ids(pre, len(rows)),
                _sorted_ids(add, len(rows)), strict=True):
            if not pre_mask & neg_mask:  # else a contradictory precondition: never applicable
                actions.append(GroundAction(name, args, pre_mask, neg_mask, add_mask, delete_mask,
                                                      pre_ids, add_ids))

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

