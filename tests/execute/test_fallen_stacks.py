"""Physics' stack check: a stack the plan has standing must stand in the simulated scene."""

from __future__ import annotations

from kitchen_tamp.execute.physics.execution import fallen_stacks
from kitchen_tamp.kitchen import build_kitchen_for_task, load_kitchen_map
from kitchen_tamp.planning import load_task
from kitchen_tamp.shipped_kitchens import kitchen_folder
from kitchen_tamp.world import Pose

TOWERS = kitchen_folder("benchmarks") / "towers"


def test_a_stack_that_stands_passes_and_one_knocked_over_is_named() -> None:
    task = load_task(TOWERS / "problem_sussman.pddl")
    kitchen_map = load_kitchen_map(TOWERS / "scene.toml", TOWERS / "domain.pddl")
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        planned = task.state_atoms(task.initial_state)
        assert ("on", "c", "a") in planned
        assert fallen_stacks(kitchen, planned) == []
        a, c = kitchen.box("a").base_pose(), kitchen.box("c").base_pose()
        beside = Pose((a.position[0], a.position[1] + 0.12, a.position[2]), c.quaternion)
        kitchen.box("c").reset_base_pose(beside)  # c fell off a, onto the table beside it
        assert fallen_stacks(kitchen, planned) == ["the stack of c on a fell (c rests on table)"]
