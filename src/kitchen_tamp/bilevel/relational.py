"""Relational abstractions from a grounded PDDL task.

Abstract states are the task's states (bitsets of atom ids), abstract actions
its :class:`~kitchen_tamp.planning.GroundAction` s, successors and goal come
from the task, and abstract plans from :func:`kitchen_tamp.planning.iter_plans`
(shortest first, equal lengths in seeded random order). The caller supplies
Psi as the atoms true in a low-level state, and one trajectory sampler per
operator name.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import Abstraction, AbstractPlan, AbstractPlanGenerator
from kitchen_tamp.bilevel.problem import BilevelProblem, TrajectorySampler
from kitchen_tamp.planning import Atom, GroundAction, State, Task, atom_text, iter_plans

X = TypeVar("X")
U = TypeVar("U")


def describe_state(task: Task, state: State) -> str:
    """The atoms of ``state`` as PDDL text, sorted: ``(armClear) (boxOn spam countertop)``."""
    return " ".join(atom_text(atom) for atom in sorted(task.state_atoms(state)))


def relational_abstraction(
    task: Task, atoms_of: Callable[[X], Iterable[Atom]]
) -> Abstraction[X, State, GroundAction]:
    """Psi(x) = the task state of the atoms ``atoms_of(x)`` (atoms the task does not track are ignored)."""
    return Abstraction(
        abstract_state=lambda x: task.state_from_atoms(atoms_of(x)),
        successors=task.successors,
        is_goal=task.is_goal,
        describe=lambda state: describe_state(task, state),
    )


def relational_plan_generator(
    task: Task, *, max_length: int | None = None
) -> AbstractPlanGenerator[State, GroundAction]:
    """Abstract plans from ``iter_plans``, starting from whatever abstract state the planner asks for."""

    def generate(initial: State, rng: np.random.Generator) -> Iterator[AbstractPlan[State, GroundAction]]:
        search_task = task
        if initial != task.initial_state:
            search_task = task.starting_from(initial)
        for actions in iter_plans(search_task, rng=rng, max_length=max_length):
            states = [initial]
            for action in actions:
                states.append(action.apply(states[-1]))
            yield AbstractPlan(tuple(states), actions)

    return generate


def samplers_by_operator(
    samplers: Mapping[str, TrajectorySampler[X, U, State, GroundAction]],
) -> Callable[[GroundAction], TrajectorySampler[X, U, State, GroundAction]]:
    """``sampler_for`` that picks a sampler by the action's operator name (case-insensitive, as in PDDL)."""
    by_name = {name.lower(): sampler for name, sampler in samplers.items()}

    def sampler_for(action: GroundAction) -> TrajectorySampler[X, U, State, GroundAction]:
        sampler = by_name.get(action.name.lower())
        if sampler is None:
            raise KeyError(f"no trajectory sampler for operator {action.name!r} "
                           f"(have: {', '.join(sorted(samplers)) or 'none'})")
        return sampler

    return sampler_for


def relational_problem(
    task: Task,
    initial_state: X,
    atoms_of: Callable[[X], Iterable[Atom]],
    sampler_for: Callable[[GroundAction], TrajectorySampler[X, U, State, GroundAction]],
    *,
    transition: Callable[[X, U], X] | None = None,
    max_plan_length: int | None = None,
) -> BilevelProblem[X, U, State, GroundAction]:
    """A bilevel problem whose abstraction and abstract plans come from ``task``."""
    return BilevelProblem(
        initial_state=initial_state,
        abstraction=relational_abstraction(task, atoms_of),
        sampler_for=sampler_for,
        transition=transition,
        plan_generator=relational_plan_generator(task, max_length=max_plan_length),
    )
