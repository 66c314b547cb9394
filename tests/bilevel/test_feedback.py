"""Failures that teach the abstract search: learned obstructions and pruned actions, on the
nonmonotonic benchmark's task with stand-in samplers (no simulator)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.bilevel import (
    AbstractTransition,
    BilevelResult,
    LearningPlanGenerator,
    Obstruction,
    Outcome,
    SamplingFailure,
    SesameBudgets,
    Trajectory,
    Unreachable,
    relational_plan_generator,
    relational_problem,
    sesame,
)
from kitchen_tamp.bilevel.relational import SHORTEST_FIRST_MAX_ACTIONS, task_with_facts
from kitchen_tamp.planning import Atom, GroundAction, State, Task, load_task, validate_plan

BENCHMARKS = Path(__file__).resolve().parents[2] / "src" / "kitchen_tamp" / "shipped_kitchens" / "benchmarks"
AtomSet = frozenset[Atom]

BLOCKERS = {"red_box": "red_blocker", "blue_box": "blue_blocker"}


def nonmonotonic_task() -> Task:
    return load_task(BENCHMARKS / "nonmonotonic" / "problem.pddl")


class BlockedPicks:
    """x is the set of true atoms; every action applies its effects, except that picking a box
    whose blocker is still on the table fails, saying so (or not, with ``teach=False``)."""

    def __init__(self, task: Task, teach: bool = True) -> None:
        self.task, self.teach = task, teach

    def __call__(
        self, state: AtomSet, transition: AbstractTransition[State, GroundAction], rng: np.random.Generator
    ) -> Trajectory[AtomSet, str]:
        action = transition.action
        blocker = BLOCKERS.get(action.args[0]) if action.name == "pick" else None
        if blocker is not None and ("on", blocker, "table") in state:
            fact = Obstruction(("pick", action.args), frozenset({("on", blocker, "table")}), (blocker,))
            raise SamplingFailure(f"{blocker} is in the way", (fact,) if self.teach else ())
        after = frozenset(self.task.state_atoms(action.apply(self.task.state_from_atoms(state))))
        return Trajectory((state, after), (str(action),))


Result = BilevelResult[AtomSet, str, State, GroundAction]


def solve(task: Task, teach: bool, budgets: SesameBudgets) -> Result:
    problem = relational_problem(task, task.state_atoms(task.initial_state), lambda atoms: atoms,
                                 lambda action: BlockedPicks(task, teach))
    return sesame(problem, budgets, seed=0)


def test_a_learned_obstruction_is_a_negative_precondition_of_that_action_only() -> None:
    task = nonmonotonic_task()
    fact = Obstruction(("pick", ("red_box", "table")), frozenset({("on", "red_blocker", "table")}),
                       ("red_blocker",))
    learned = task_with_facts(task, [fact])
    blocked = learned.action_named("pick", ["red_box", "table"])
    assert blocked is not None and not blocked.applicable(learned.initial_state)
    other = learned.action_named("pick", ["blue_box", "table"])
    assert other is not None and other.applicable(learned.initial_state)
    assert len(learned.actions) == len(task.actions)
    unreachable = Unreachable("red_plate", frozenset({("place", ("red_box", "red_plate"))}))
    pruned = task_with_facts(task, [unreachable])
    assert pruned.action_named("place", ["red_box", "red_plate"]) is None
    assert len(pruned.actions) == len(task.actions) - 1


def test_the_generator_learns_each_fact_once_and_refutes_the_plans_it_rules_out() -> None:
    task = nonmonotonic_task()
    generator = relational_plan_generator(task)
    assert isinstance(generator, LearningPlanGenerator)
    first = next(generator(task.initial_state, np.random.default_rng(0)))
    assert len(first) == 4 and generator.admits(first)
    fact = Obstruction(("pick", ("red_box", "table")), frozenset({("on", "red_blocker", "table")}),
                       ("red_blocker",))
    assert generator.learn([fact, "not a fact"]) == [fact]
    assert generator.learn([fact]) == []
    assert not generator.admits(first)
    again = next(generator(task.initial_state, np.random.default_rng(0)))
    moves = [action.text for action in again.actions]
    assert moves.index("(pick red_blocker table)") < moves.index("(pick red_box table)")
    assert validate_plan(task, again.actions).valid


def test_sesame_drops_a_refuted_plan_at_once_and_moves_the_obstructions_first() -> None:
    task = nonmonotonic_task()
    result = solve(task, teach=True, budgets=SesameBudgets(max_plans=5, samples_per_step=4))
    assert result.solved and result.plan is not None
    assert len(result.learned) == 2
    refuted = [a for a in result.attempts if a.outcome is Outcome.PLAN_REFUTED]
    assert refuted and all(sum(step.failures for step in a.steps) == 1 for a in refuted)  # no resampling
    moves = [step.transition.action.text for step in result.plan.steps]
    for box, blocker in BLOCKERS.items():
        assert moves.index(f"(pick {blocker} table)") < moves.index(f"(pick {box} table)")


def test_without_feedback_the_same_budgets_run_out_on_plans_that_pick_behind_the_blockers() -> None:
    task = nonmonotonic_task()
    result = solve(task, teach=False, budgets=SesameBudgets(max_plans=5, samples_per_step=4))
    assert not result.solved and not result.learned
    assert result.outcome is Outcome.PLAN_BUDGET


def test_plans_refuted_by_what_they_taught_do_not_count_against_the_plan_budget() -> None:
    task = nonmonotonic_task()
    budgets = SesameBudgets(max_plans=1, samples_per_step=4)
    result = solve(task, teach=True, budgets=budgets)
    refuted = [a for a in result.attempts if a.outcome is Outcome.PLAN_REFUTED]
    assert result.solved and len(refuted) == len(result.learned) == 2
    assert result.counts.abstract_plans == 3  # the report still counts every plan tried
    untaught = solve(task, teach=False, budgets=budgets)
    assert untaught.outcome is Outcome.PLAN_BUDGET and untaught.counts.abstract_plans == 1


@pytest.mark.parametrize("family", ["sort_clutter"])
def test_a_large_task_yields_plans_best_first_without_delay(family: str) -> None:
    task = load_task(BENCHMARKS / family / "problem.pddl")
    assert len(task.actions) > SHORTEST_FIRST_MAX_ACTIONS
    generator = relational_plan_generator(task)
    fact = Obstruction(("pick", ("blue2", "table")), frozenset({("on", "red1", "table")}), ("red1",))
    generator.learn([fact])
    plan = next(generator(task.initial_state, np.random.default_rng(0)))
    moves = [action.text for action in plan.actions]
    assert validate_plan(task, plan.actions).valid
    assert moves.index("(pick red1 table)") < moves.index("(pick blue2 table)")


def test_facts_that_leave_no_plan_end_the_enumeration() -> None:
    task = load_task(BENCHMARKS / "blocked" / "problem.pddl")
    generator = relational_plan_generator(task)
    on_table = {"green": ("on", "blocker", "table"), "blocker": ("on", "green", "table")}
    generator.learn([Obstruction(("pick", (box, "table")), frozenset({atom}), (atom[1],))
                     for box, atom in on_table.items()])  # each in the way of the other
    assert next(generator(task.initial_state, np.random.default_rng(0)), None) is None
