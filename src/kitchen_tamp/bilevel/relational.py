"""Relational abstractions from a grounded PDDL task.

Abstract states are the task's states (bitsets of atom ids), abstract actions
its :class:`~kitchen_tamp.planning.GroundAction` s, successors and goal come
from the task, and abstract plans from :func:`kitchen_tamp.planning.iter_plans`
(shortest first, equal lengths in seeded random order). On tasks of more than
``SHORTEST_FIRST_MAX_ACTIONS`` actions the first plan comes from greedy best-first
search (h_FF, the planning package's ``gbfs``) and the next ones best first by h_FF:
shortest first is breadth-first there, and the relaxation behind h_FF does not see
learned negative preconditions, so a tree search alone wanders. The caller supplies
Psi as the atoms true in a low-level state, and one trajectory sampler per
operator name.

The plan generator learns (``kitchen_tamp.bilevel.feedback``): an ``Obstruction``
adds its atoms to the action's negative preconditions, an ``Unreachable`` removes
its actions, and later plans come from the task with what was learned.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Final, TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import Abstraction, AbstractPlan
from kitchen_tamp.bilevel.feedback import ActionKey, LearnedFact, Obstruction, Unreachable
from kitchen_tamp.bilevel.problem import BilevelProblem, TrajectorySampler
from kitchen_tamp.planning import Atom, GroundAction, State, Task, atom_text, iter_plans, plan
from kitchen_tamp.planning.heuristics import HeuristicName

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


MAX_EXPANSIONS: Final = {"hmax": 500_000, "hff": 5_000}
"""Nodes one enumeration of abstract plans may expand, by its heuristic: what failures taught
may leave no plan, and an enumeration would then never end. Shortest first (h_max, cheap) takes
up to 50,000 for the five plans of the shipped problems (about a second), best first (h_FF, a
relaxed plan per node) far fewer."""
SHORTEST_FIRST_MAX_ACTIONS: Final = 200
"""Up to this many ground actions, abstract plans come shortest first (h_max); above it, the
first from greedy best-first search and the next best first by h_FF: h_max leaves the
enumeration breadth-first, and a 400-action task then yields no plan in minutes."""
LARGE_TASK_SEARCH: Final = "gbfs"
LARGE_TASK_SEARCH_S: Final = 60.0


def key_of(action: GroundAction) -> ActionKey:
    return action.name, action.args


def task_with_facts(task: Task, facts: Iterable[LearnedFact]) -> Task:
    """``task`` with the learned facts: obstructions as negative preconditions (atoms the task
    does not track cannot hold, and are dropped), unreachable actions removed."""
    absent: dict[ActionKey, int] = {}
    pruned: set[ActionKey] = set()
    for fact in facts:
        if isinstance(fact, Obstruction):
            mask = task.state_from_atoms(fact.absent)
            absent[fact.action] = absent.get(fact.action, 0) | mask
        else:
            pruned |= fact.actions
    actions = []
    for action in task.actions:
        key = key_of(action)
        if key in pruned:
            continue
        extra = absent.get(key, 0)
        actions.append(replace(action, pre_neg=action.pre_neg | extra) if extra else action)
    return replace(task, actions=tuple(actions))


@dataclass
class RelationalPlanGenerator:
    """Abstract plans from ``iter_plans`` over the task with every fact learned so far,
    starting from whatever abstract state the planner asks for."""

    task: Task
    max_length: int | None = None
    facts: list[LearnedFact] = field(default_factory=list)
    learned_task: Task | None = None

    def current_task(self) -> Task:
        """The task with what was learned."""
        return self.task if self.learned_task is None else self.learned_task

    def __call__(
        self, initial: State, rng: np.random.Generator
    ) -> Iterator[AbstractPlan[State, GroundAction]]:
        search_task = self.current_task()
        if initial != search_task.initial_state:
            search_task = search_task.starting_from(initial)
        large = len(self.task.actions) > SHORTEST_FIRST_MAX_ACTIONS
        first: tuple[GroundAction, ...] | None = None
        if large:
            first = plan(search_task, LARGE_TASK_SEARCH, time_budget=LARGE_TASK_SEARCH_S).plan
            if first is not None:
                yield _abstract_plan(initial, first)
        heuristic: HeuristicName = "hff" if large else "hmax"
        for actions in iter_plans(search_task, rng=rng, max_length=self.max_length, heuristic=heuristic,
                                  max_expansions=MAX_EXPANSIONS[heuristic]):
            if actions != first:
                yield _abstract_plan(initial, actions)

    def learn(self, facts: Sequence[object]) -> list[object]:
        """Take in the obstructions and unreachable actions among ``facts`` not known yet."""
        new: list[object] = [
            fact for fact in dict.fromkeys(facts)
            if isinstance(fact, Obstruction | Unreachable) and fact not in self.facts]
        if new:
            self.facts.extend(fact for fact in new if isinstance(fact, Obstruction | Unreachable))
            self.learned_task = task_with_facts(self.task, self.facts)
        return new

    def admits(self, plan: AbstractPlan[State, GroundAction]) -> bool:
        """Whether every step of ``plan`` is an action of the learned task, applicable where it is."""
        actions = {key_of(action): action for action in self.current_task().actions}
        for state, step in zip(plan.states, plan.actions, strict=False):
            action = actions.get(key_of(step))
            if action is None or not action.applicable(state):
                return False
        return True


def _abstract_plan(initial: State, actions: tuple[GroundAction, ...]) -> AbstractPlan[State, GroundAction]:
    states = [initial]
    for action in actions:
        states.append(action.apply(states[-1]))
    return AbstractPlan(tuple(states), actions)


def relational_plan_generator(task: Task, *, max_length: int | None = None) -> RelationalPlanGenerator:
    """Abstract plans from ``iter_plans``, learning from failures (see the module docstring)."""
    return RelationalPlanGenerator(task, max_length)


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
