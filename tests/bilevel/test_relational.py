"""The relational adapter: PDDL tasks as abstractions, iter_plans as the abstract plan generator."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.bilevel import (
    AbstractTransition,
    SamplingFailure,
    SesameBudgets,
    Trajectory,
    relational_plan_generator,
    relational_problem,
    samplers_by_operator,
    sesame,
)
from kitchen_tamp.bilevel.toy_rooms import (
    ROOMS_DOMAIN,
    RoomsScene,
    blocked_doorway,
    relational_rooms_problem,
    rooms_problem_pddl,
)
from kitchen_tamp.planning import Atom, GroundAction, State, Task, load_task, validate_plan

REPO = Path(__file__).resolve().parents[2]

AtomSet = frozenset[Atom]


def rooms_task(scene: RoomsScene, directory: Path) -> Task:
    (directory / "rooms_domain.pddl").write_text(ROOMS_DOMAIN)
    (directory / "rooms_problem.pddl").write_text(rooms_problem_pddl(scene))
    return load_task(directory / "rooms_problem.pddl", directory / "rooms_domain.pddl")


def test_the_toy_rooms_as_pddl_switch_plans_like_the_native_abstraction(tmp_path: Path) -> None:
    scene = blocked_doorway()
    task = rooms_task(scene, tmp_path)
    result = sesame(relational_rooms_problem(scene, task), seed=0)
    assert result.solved and result.counts.abstract_plans == 2
    assert result.plan is not None
    assert [str(step.transition.action) for step in result.plan.steps] == [
        "go A-D A D", "go D-E D E", "go E-F E F", "go C-F F C"]
    assert validate_plan(task, [step.transition.action for step in result.plan.steps]).valid
    assert scene.world.path_hit(result.plan.trajectory.states) is None


class KitchenByEffects:
    """A stand-in for the kitchen's samplers: x is the set of true atoms and every action just
    applies its effects, except that the first ``refusals`` samples of ``refused`` fail."""

    def __init__(self, task: Task, refused: str = "", refusals: int = 0) -> None:
        self.task, self.refused, self.refusals = task, refused.lower(), refusals

    def __call__(
        self, state: AtomSet, transition: AbstractTransition[State, GroundAction], rng: np.random.Generator
    ) -> Trajectory[AtomSet, str]:
        action = transition.action
        if action.name.lower() == self.refused and self.refusals > 0:
            self.refusals -= 1
            raise SamplingFailure(f"no grasp for {action}")
        after = frozenset(self.task.state_atoms(action.apply(self.task.state_from_atoms(state))))
        return Trajectory((state, after), (str(action),))


def kitchen_task() -> Task:
    return load_task(REPO / "pddl" / "problem.pddl", REPO / "pddl" / "domain.pddl")


def test_a_kitchen_plan_refines_through_the_adapter_with_backtracking() -> None:
    task = kitchen_task()
    sampler = KitchenByEffects(task, refused="placeIn", refusals=3)
    problem = relational_problem(task, task.state_atoms(task.initial_state), lambda atoms: atoms,
                                 lambda action: sampler)
    result = sesame(problem, SesameBudgets(samples_per_step=2), seed=0)
    assert result.solved and result.plan is not None
    actions = [step.transition.action for step in result.plan.steps]
    assert validate_plan(task, actions).valid
    assert task.is_goal(task.state_from_atoms(result.plan.final_state))
    assert result.counts.failures == 3 and result.counts.backtracks >= 1


def test_plans_start_from_the_abstract_state_the_planner_asks_for() -> None:
    task = kitchen_task()
    first_plan = next(iter(relational_plan_generator(task)(task.initial_state, np.random.default_rng(0))))
    midway = first_plan.states[2]
    from_midway = next(iter(relational_plan_generator(task)(midway, np.random.default_rng(0))))
    assert from_midway.states[0] == midway and task.is_goal(from_midway.states[-1])
    assert len(from_midway) == len(first_plan) - 2


def test_the_seed_orders_equally_short_kitchen_plans() -> None:
    task = load_task(REPO / "pddl" / "problem_hard.pddl", REPO / "pddl" / "domain.pddl")
    generate = relational_plan_generator(task, max_length=9)

    def order(seed: int) -> list[tuple[GroundAction, ...]]:
        return [plan.actions for plan in itertools.islice(generate(task.initial_state,
                                                                   np.random.default_rng(seed)), 5)]

    assert order(4) == order(4)
    lengths = [len(plan) for plan in order(4)]
    assert lengths[0] == 7 and lengths == sorted(lengths)


def test_samplers_are_found_by_operator_name() -> None:
    task = kitchen_task()
    sampler = KitchenByEffects(task)
    sampler_for = samplers_by_operator({"PICKUP": sampler})
    pick = next(action for action in task.actions if action.name == "pickUp")
    assert sampler_for(pick) is sampler
    place = next(action for action in task.actions if action.name == "placeOn")
    with pytest.raises(KeyError, match="no trajectory sampler for operator 'placeOn'"):
        sampler_for(place)


def test_a_mismatched_abstract_state_is_a_sampling_failure_named_in_atoms() -> None:
    task = kitchen_task()

    def standing_still(
        state: AtomSet, transition: AbstractTransition[State, GroundAction], rng: np.random.Generator
    ) -> Trajectory[AtomSet, str]:
        return Trajectory((state, state), ("wait",))

    problem = relational_problem(task, task.state_atoms(task.initial_state), lambda atoms: atoms,
                                 lambda action: standing_still)
    result = sesame(problem, SesameBudgets(max_plans=1, samples_per_step=1), seed=0)
    assert not result.solved
    message = result.graph.failed_samples[0].message
    assert message.startswith("trajectory ends in abstract state (") and ", not (" in message
