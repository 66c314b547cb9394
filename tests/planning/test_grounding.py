from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from kitchen_tamp.planning import Task, load_task
from tests.planning.conftest import DATA, KITCHEN, REPO, data_task


def test_kitchen_task_keeps_the_problem_as_written() -> None:
    task = load_task(KITCHEN / "problem.pddl")
    assert task.domain_name == "kitchen"
    assert dict(task.objects) == {"stove": "surface", "countertop": "surface",
                                  "drawer": "openable", "sugar": "box", "spam": "box"}
    assert task.init_atoms == {("boxOn", "sugar", "stove"), ("boxOn", "spam", "countertop"),
                               ("cabClear", "drawer"), ("armClear",)}
    assert task.goal_atoms == {("boxOn", "sugar", "countertop"), ("boxIn", "spam", "drawer")}
    assert task.state_atoms(task.initial_state) == task.init_atoms


def test_type_hierarchy_constants_equality_and_static_negation() -> None:
    task = data_task("delivery_two_parcels.pddl", "delivery_domain.pddl")
    drives = {action.args for action in task.actions if action.name == "drive"}
    # Both subtypes of vehicle are grounded, the constant depot is a place, there
    # is no drive from a place to itself, none along a missing road, and the
    # broken truck (a static negative precondition) never drives.
    assert drives == {("vw", "depot", "north"), ("vw", "north", "depot"),
                      ("vw", "north", "south"), ("vw", "south", "north")}
    assert task.objects["depot"] == "place"
    assert ("road", "north", "south") not in task.atoms  # static atoms leave the state
    assert ("at", "lorry", "north") in task.atoms


def test_grounding_prunes_unreachable_actions() -> None:
    task = data_task("delivery_two_parcels.pddl", "delivery_domain.pddl")
    loads = {action.args for action in task.actions if action.name == "load"}
    # The lorry never moves and is never fuelled, so nothing is loaded into it.
    assert all(vehicle == "vw" for _, vehicle, _ in loads)
    assert ("p1", "vw", "north") in loads


def test_negated_goal_literals_are_part_of_the_goal() -> None:
    task = data_task("delivery_two_parcels.pddl", "delivery_domain.pddl")
    assert task.negative_goal_atoms == {("in", "p1", "vw")}
    assert task.goal_neg != 0


def test_names_are_case_insensitive_and_keep_the_declared_spelling(tmp_path: Path) -> None:
    problem = tmp_path / "shouting.pddl"
    problem.write_text(
        "(define (problem SHOUT) (:domain KITCHEN)"
        " (:objects STOVE COUNTERTOP - SURFACE SUGAR - BOX)"
        " (:init (BOXON SUGAR STOVE) (ARMCLEAR)) (:goal (BOXON SUGAR COUNTERTOP)))")
    task = load_task(problem, KITCHEN / "domain.pddl")
    assert ("boxOn", "SUGAR", "STOVE") in task.init_atoms


def test_grounding_many_objects_builds_only_reachable_actions(tmp_path: Path) -> None:
    balls = [f"ball{i}" for i in range(40)]
    problem = tmp_path / "many.pddl"
    problem.write_text(
        "(define (problem many) (:domain kitchen) (:objects stove countertop - surface"
        f" drawer - openable {' '.join(balls)} - box)"
        " (:init (armClear) (cabClear drawer) (surfClear countertop)"
        + "".join(f" (boxOn {b} stove)" for b in balls)
        + ") (:goal (boxIn ball0 drawer)))")
    task = load_task(problem, KITCHEN / "domain.pddl")
    # 1 open + per box: 2 pickUp, 1 cabPickUp, 2 placeOn, 1 placeIn.
    assert len(task.actions) == 1 + 6 * len(balls)


def test_ground_action_order_does_not_depend_on_hash_seeds() -> None:
    script = ("from kitchen_tamp.planning import load_task, plan\n"
              f"t = load_task({str(DATA / 'delivery_two_parcels.pddl')!r},"
              f" {str(DATA / 'delivery_domain.pddl')!r})\n"
              "print([str(a) for a in t.actions]); print(plan(t, 'gbfs').plan)")
    outputs = {
        subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True,
                       cwd=REPO, env={"PYTHONHASHSEED": seed}).stdout
        for seed in ("1", "2", "3")
    }
    assert len(outputs) == 1


def _generated_problems() -> dict[str, tuple[str, str]]:
    sys.path.insert(0, str(REPO / "benchmarks"))
    from pddl_generators import blocks_world, gripper, scaled_kitchen

    return {"blocks": blocks_world(4, 1), "gripper": gripper(3), "kitchen": scaled_kitchen(3, 4, 2, 0)}


def test_grounding_finds_exactly_the_relaxed_reachable_bindings(tmp_path: Path) -> None:
    from kitchen_tamp.planning.grounding import ground
    from kitchen_tamp.planning.reading.package_reader import (
        domain_syntax,
        parse_domain,
        parse_problem,
        problem_syntax,
    )
    from kitchen_tamp.planning.schemas import translate
    from tests.planning.brute_force import naive_ground_action_names
    from tests.planning.conftest import SMALL_TASKS

    pairs = [(Path(p), Path(d)) for p, d in SMALL_TASKS.values()]
    pairs += [(DATA / "delivery_unsolvable.pddl", DATA / "delivery_domain.pddl")]
    for name, (domain_text, problem_text) in _generated_problems().items():
        (tmp_path / f"{name}-domain.pddl").write_text(domain_text)
        (tmp_path / f"{name}.pddl").write_text(problem_text)
        pairs.append((tmp_path / f"{name}.pddl", tmp_path / f"{name}-domain.pddl"))
    for problem, domain in pairs:
        parsed_domain, dsrc = parse_domain(domain)
        parsed_problem, psrc = parse_problem(problem)
        lifted = translate(domain_syntax(parsed_domain, dsrc), problem_syntax(parsed_problem, psrc),
                           dsrc, psrc)
        task = ground(lifted)
        assert {(a.name, a.args) for a in task.actions} == naive_ground_action_names(lifted), problem.name


def test_successor_table_yields_exactly_the_applicable_actions(small_task: Task) -> None:
    from tests.planning.brute_force import reachable_states

    for state in reachable_states(small_task):
        expected = [a for a in small_task.actions if a.applicable(state)]
        listed = list(small_task.applicable_actions(state))
        assert sorted(map(str, listed)) == sorted(map(str, expected))
        assert [(a, a.apply(state)) for a in listed] == list(small_task.successors(state))
        for action in listed:
            assert small_task.action_between(state, action.apply(state)).apply(state) == action.apply(state)
