"""Conditions geometry does not show (clean, cooked), derived by the one rule the planner and both
judges share: an action's condition effects hold when its skill's requirement holds in the scene."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.kitchen import (
    abstract_state,
    build_kitchen_for_task,
    load_kitchen_map,
    record_conditions,
    sample_targets,
)
from kitchen_tamp.planning import GroundAction, Task, load_task
from kitchen_tamp.shipped_kitchens import kitchen_folder

KITCHEN = kitchen_folder("benchmarks") / "kitchen"


def action(task: Task, text: str) -> GroundAction:
    name, *args = text.split()
    found = task.action_named(name, args)
    assert found is not None
    return found


def test_a_wash_away_from_the_sink_sets_nothing_and_says_why() -> None:
    task = load_task(KITCHEN / "problem_radish.pddl")
    kitchen_map = load_kitchen_map(KITCHEN / "scene.toml", KITCHEN / "domain.pddl")
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        problem = record_conditions(kitchen, task, action(task, "wash radish sink"))
        assert problem == "(wash radish sink) sets no conditions: radish rests on tray, not on sink"
        assert ("clean", "radish") not in abstract_state(kitchen, task.objects)
        for step in ("pick radish tray", "place radish sink"):
            name, *args = step.split()
            sample_targets(kitchen, name, tuple(args), np.random.default_rng(0)).apply(kitchen)
        assert record_conditions(kitchen, task, action(task, "wash radish sink")) is None
        assert ("clean", "radish") in abstract_state(kitchen, task.objects)
        cook = record_conditions(kitchen, task, action(task, "cook radish hob"))
        assert cook == "(cook radish hob) sets no conditions: radish rests on sink, not on hob"
        assert ("cooked", "radish") not in abstract_state(kitchen, task.objects)
