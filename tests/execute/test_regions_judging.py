"""Both judges on the regions domain: conditions derived from the replayed (and simulated) scene
as the planner derives them, stacks that stay standing under physics."""

from __future__ import annotations

import pytest

from kitchen_tamp.execute import verify_trajectory
from kitchen_tamp.execute.physics.execution import execute_under_physics
from kitchen_tamp.kitchen import build_kitchen_for_task, load_kitchen_map
from kitchen_tamp.planning import load_task
from kitchen_tamp.refinement import SamplingMotionBackend, refine_with_sesame
from kitchen_tamp.shipped_kitchens import kitchen_folder

BENCHMARKS = kitchen_folder("benchmarks")


@pytest.mark.slow
@pytest.mark.parametrize(("family", "problem", "derived"), [
    ("kitchen", "problem_radish.pddl", "(cooked radish)"),
    ("towers", "problem_sussman.pddl", "(on a b)"),
])
def test_both_judges_verify_a_regions_run_deriving_its_conditions_and_stacks(
    family: str, problem: str, derived: str
) -> None:
    folder = BENCHMARKS / family
    task = load_task(folder / problem)
    kitchen_map = load_kitchen_map(folder / "scene.toml", folder / "domain.pddl")
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        refined = refine_with_sesame(kitchen, task, SamplingMotionBackend(), seed=0).refined
    assert refined is not None
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        judged = verify_trajectory(kitchen, task, refined.trajectory)
    assert judged.verified, judged.problems
    assert derived in judged.final_atoms
    physics = execute_under_physics(task, refined.trajectory, judged, kitchen_map)
    assert physics.verified, physics.problems
    assert derived in physics.final_atoms
