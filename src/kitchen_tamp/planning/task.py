"""The grounded STRIPS task that every search works on.

Atoms are numbered; a state is a Python ``int`` used as a bitset (bit ``i`` set
means atom ``i`` holds). Bitsets make applicability a mask test, successors two
bit operations, and states hashable for free.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

Atom = tuple[str, ...]
"""A ground atom as (predicate, arg, ...), e.g. ``("boxOn", "sugar", "stove")``."""

State = int
"""A set of atom ids as a bitset."""


def atom_text(atom: Atom) -> str:
    """PDDL text of an atom or a ground action: ``(boxOn sugar stove)``, ``(pickUp spam countertop)``.

    The one place this text is written: plans, messages and reports all use it."""
    return "(" + " ".join(atom) + ")"


def bits(mask: int) -> Iterator[int]:
    """The ids of the set bits of ``mask``, lowest first."""
    while mask:
        low = mask & -mask
        yield low.bit_length() - 1
        mask ^= low


def mask_of(ids: Iterable[int]) -> int:
    """The bitset with exactly the given ids set."""
    mask = 0
    for i in ids:
        mask |= 1 << i
    return mask


@dataclass(frozen=True, slots=True)
class GroundAction:
    """One grounded operator with unit cost.

    ``pre``/``pre_neg`` are the atoms that must hold / must not hold, ``add`` and
    ``delete`` its effects, all as bitsets over the task's atom ids. The id tuples
    are the same sets, kept for heuristics that loop over single atoms.
    """

    name: str
    args: tuple[str, ...]
    pre: int
    pre_neg: int
    add: int
    delete: int
    pre_ids: tuple[int, ...]
    add_ids: tuple[int, ...]

    def __str__(self) -> str:
        return " ".join((self.name, *self.args))

    @property
    def text(self) -> str:
        """The IPC plan-file form: ``(pickUp spam countertop)``."""
        return atom_text((self.name, *self.args))

    def applicable(self, state: State) -> bool:
        return state & self.pre == self.pre and not state & self.pre_neg

    def apply(self, state: State) -> State:
        return (state & ~self.delete) | self.add


ActionEntry = tuple[int, int, int, int, int]
"""One action as the searches see it: (pre, pre_neg, ~delete, add, index into ``Task.actions``)."""


SuccessorTable = tuple[int, dict[int, tuple[ActionEntry, ...]], tuple[ActionEntry, ...]]
"""Actions grouped for fast successor generation: ``(key_mask, by_key, unconditional)``.

``by_key`` maps the bit of an atom (``1 << id``) to the actions keyed by it,
``key_mask`` is the union of those bits and ``unconditional`` holds the
actions without positive preconditions. A child is ``(state & keep) | add``.
"""


@dataclass(frozen=True)
class Task:
    """A grounded planning task.

    ``init_atoms`` is the problem's ``:init`` exactly as written (static atoms
    included); ``atoms`` holds only the fluent atoms that are relaxed-reachable,
    which are the ones states are made of. Tables derived from the task
    (``atom_ids``, ``key_atoms``, ``successor_table``) are built on first use
    and kept beside the fields.
    """

    name: str
    domain_name: str
    objects: Mapping[str, str]
    init_atoms: frozenset[Atom]
    goal_atoms: frozenset[Atom]
    negative_goal_atoms: frozenset[Atom]
    atoms: tuple[Atom, ...]
    initial_state: State
    goal: int
    goal_neg: int
    actions: tuple[GroundAction, ...]
    unreachable_goal_atoms: frozenset[Atom] = field(default_factory=frozenset)

    def starting_from(self, state: State) -> Task:
        """The same task from another initial state (derived tables are rebuilt when asked for)."""
        return replace(self, initial_state=state)

    @cached_property
    def atom_ids(self) -> Mapping[Atom, int]:
        """Each fluent atom's id."""
        return {atom: i for i, atom in enumerate(self.atoms)}

    @property
    def trivially_unsolvable(self) -> bool:
        """Some goal atom can never become true, or a goal is contradictory."""
        return bool(self.unreachable_goal_atoms) or bool(self.goal & self.goal_neg)

    def is_goal(self, state: State) -> bool:
        return (
            not self.unreachable_goal_atoms
            and state & self.goal == self.goal
            and not state & self.goal_neg
        )

    @cached_property
    def key_atoms(self) -> list[int]:
        """Each action's key atom: its precondition atom used by the fewest actions (-1: none).

        An action cannot apply (or fire, in a relaxed exploration) before its
        key atom holds, so grouping actions by key lets a loop skip the groups
        whose key is false.
        """
        uses = [0] * len(self.atoms)
        for action in self.actions:
            for atom in action.pre_ids:
                uses[atom] += 1
        return [min(action.pre_ids, key=lambda atom: (uses[atom], atom)) if action.pre_ids else -1
                for action in self.actions]

    @cached_property
    def keyed_action_indices(self) -> tuple[list[int], list[list[int]]]:
        """The actions without a key atom, and per atom the actions keyed on it, as indices in index
        order: the order ``successor_indices`` tries them in, as the compiled searches lay them out."""
        unconditional: list[int] = []
        by_key: list[list[int]] = [[] for _ in self.atoms]
        for index, key in enumerate(self.key_atoms):
            (by_key[key] if key >= 0 else unconditional).append(index)
        return unconditional, by_key

    @cached_property
    def successor_table(self) -> SuccessorTable:
        """Actions keyed by their least common precondition atom.

        A state then only tests the actions whose key atom it contains, instead
        of every action. The searches loop over this table directly; see
        ``SuccessorTable`` for the layout and ``successors`` for the loop.
        """
        keyed: dict[int, list[ActionEntry]] = {}
        unconditional: list[ActionEntry] = []
        for index, (action, key) in enumerate(zip(self.actions, self.key_atoms, strict=True)):
            entry = (action.pre, action.pre_neg, ~action.delete, action.add, index)
            if key >= 0:
                keyed.setdefault(1 << key, []).append(entry)
            else:
                unconditional.append(entry)
        return (mask_of(k.bit_length() - 1 for k in keyed), {k: tuple(v) for k, v in keyed.items()},
                tuple(unconditional))

    def applicable_actions(self, state: State) -> Iterator[GroundAction]:
        """The actions applicable in ``state``, in a fixed order for a given state."""
        actions = self.actions
        for _, index in self.successor_indices(state):
            yield actions[index]

    def successors(self, state: State) -> Iterator[tuple[GroundAction, State]]:
        actions = self.actions
        for child, index in self.successor_indices(state):
            yield actions[index], child

    def successor_indices(self, state: State) -> list[tuple[State, int]]:
        """``(child, action index)`` for each applicable action, in the order of ``successors``."""
        key_mask, keyed, unconditional = self.successor_table
        out = [((state & keep) | add, index) for pre, neg, keep, add, index in unconditional
               if not state & neg]
        keys = state & key_mask
        while keys:
            low = keys & -keys
            keys ^= low
            for pre, neg, keep, add, index in keyed[low]:
                if state & pre == pre and not state & neg:
                    out.append(((state & keep) | add, index))
        return out

    def action_between(self, state: State, child: State) -> GroundAction:
        """The first action (in ``successors`` order) that leads from ``state`` to ``child``.

        Searches store only parent states; plans are read back with this.
        """
        for action, successor in self.successors(state):
            if successor == child:
                return action
        raise ValueError("no action leads from the given state to the given child")

    def state_atoms(self, state: State) -> frozenset[Atom]:
        """The fluent atoms true in ``state``."""
        return frozenset(self.atoms[i] for i in bits(state))

    def state_from_atoms(self, atoms: Iterable[Atom]) -> State:
        """The bitset of the given atoms; atoms the task does not track are ignored."""
        ids = self.atom_ids
        return mask_of(ids[a] for a in atoms if a in ids)

    def action_named(self, name: str, args: Sequence[str]) -> GroundAction | None:
        """The ground action ``name(args)``, compared case-insensitively as in PDDL."""
        key = (name.lower(), tuple(a.lower() for a in args))
        for action in self.actions:
            if (action.name.lower(), tuple(a.lower() for a in action.args)) == key:
                return action
        return None
