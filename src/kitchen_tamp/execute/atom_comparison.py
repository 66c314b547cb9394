"""Comparing the atoms a scene shows with the atoms a plan expects: one wording for both judges.

The kinematic judge (``verification``) and execution under physics
(``physics.execution``) both ask, after each action, whether Ψ(scene) is the
planned state, and at the end which goal literals hold.
"""

from __future__ import annotations

from kitchen_tamp.planning import Atom, Task, atom_text


def atoms_text(atoms: frozenset[Atom]) -> list[str]:
    """The atoms as sorted PDDL text."""
    return sorted(atom_text(a) for a in atoms)


def state_mismatch(observed: frozenset[Atom], expected: frozenset[Atom]) -> str | None:
    """How ``observed`` differs from ``expected`` in words, or None when they are equal."""
    if observed == expected:
        return None
    return (
        f"the scene shows {atoms_text(observed - expected)} "
        f"but the plan expects {atoms_text(expected - observed)}"
    )


def goal_literals(task: Task, final: frozenset[Atom]) -> dict[str, bool]:
    """Each goal literal of ``task`` (``(not ...)`` for negated ones) and whether ``final`` satisfies it."""
    literals = {atom_text(a): a in final for a in sorted(task.goal_atoms)}
    literals.update({f"(not {atom_text(a)})": a not in final for a in sorted(task.negative_goal_atoms)})
    return literals


def all_hold(literals: dict[str, bool]) -> bool:
    """Whether there is at least one literal and every one holds."""
    return bool(literals) and all(literals.values())
