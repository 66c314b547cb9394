"""The grounded STRIPS task that every search works on.

Atoms are numbered; a state is a Python ``int`` used as a bitset (bit ``i`` set
means atom ``i`` holds). Bitsets make applicability a mask test, successors two
bit operations, and states hashable for free; see ``benchmarks/symbolic.py`` for
the measured difference against frozensets of strings.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field

Atom = tuple[str, ...]
"""A ground atom as (predicate, arg, ...), e.g. ``("boxOn", "sugar", "stove")``."""

State = int
"""A set of atom ids as a bitset."""


def atom_text(atom: Atom) -> str:
    """PDDL text of an atom: ``(boxOn sugar stove)``."""
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


@dataclass(frozen=True)
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
    pre_ids: tuple[int, ...] = field(compare=False)
    add_ids: tuple[int, ...] = field(compare=False)

    def __str__(self) -> str:
        return " ".join((self.name, *self.args))

    @property
    def text(self) -> str:
        """The IPC plan-file form: ``(pickUp spam countertop)``."""
        return "(" + str(self) + ")"

    def applicable(self, state: State) -> bool:
        return state & self.pre == self.pre and not state & self.pre_neg

    def apply(self, state: State) -> State:
        return (state & ~self.delete) | self.add


@dataclass(frozen=True)
class Task:
    """A grounded planning task.

    ``init_atoms`` is the problem's ``:init`` exactly as written (static atoms
    included); ``atoms`` holds only the fluent atoms that are relaxed-reachable,
    which are the ones states are made of.
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
    unreachable_goal_atoms: frozenset[Atom] = frozenset()

    @property
    def atom_ids(self) -> Mapping[Atom, int]:
        ids = self.__dict__.get("_atom_ids")
        if ids is None:
            ids = {atom: i for i, atom in enumerate(self.atoms)}
            object.__setattr__(self, "_atom_ids", ids)
        return ids

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

    def _successor_index(self) -> tuple[int, dict[int, tuple[GroundAction, ...]], tuple[GroundAction, ...]]:
        """Actions keyed by their least common precondition atom, built once.

        A state then only looks at the actions whose key atom it contains,
        instead of testing every action.
        """
        index = self.__dict__.get("_successor_index_cache")
        if index is None:
            uses = [0] * len(self.atoms)
            for action in self.actions:
                for atom in action.pre_ids:
                    uses[atom] += 1
            keyed: dict[int, list[GroundAction]] = {}
            unconditional: list[GroundAction] = []
            for action in self.actions:
                if action.pre_ids:
                    key = min(action.pre_ids, key=lambda atom: (uses[atom], atom))
                    keyed.setdefault(key, []).append(action)
                else:
                    unconditional.append(action)
            index = (mask_of(keyed), {k: tuple(v) for k, v in keyed.items()}, tuple(unconditional))
            object.__setattr__(self, "_successor_index_cache", index)
        return index

    def applicable_actions(self, state: State) -> Iterator[GroundAction]:
        """The actions applicable in ``state``, in a fixed order for a given state."""
        key_mask, keyed, unconditional = self._successor_index()
        for action in unconditional:
            if not state & action.pre_neg:
                yield action
        for atom in bits(state & key_mask):
            for action in keyed[atom]:
                if state & action.pre == action.pre and not state & action.pre_neg:
                    yield action

    def successors(self, state: State) -> Iterator[tuple[GroundAction, State]]:
        for action in self.applicable_actions(state):
            yield action, (state & ~action.delete) | action.add

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
