from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from kitchen_tamp.planning import load_task
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
