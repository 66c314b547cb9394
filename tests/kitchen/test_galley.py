"""The second shipped kitchen (the galley: two drawers, a side table, four boxes) is laid out
from its problems' :init with the shared domain, and its drawers move independently."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import abstract_state, build_kitchen_for_task, load_kitchen_map
from kitchen_tamp.kitchen.scene.regions import box_corners
from kitchen_tamp.planning import load_task, plan
from kitchen_tamp.shipped_kitchens import default_domain_path, kitchen_folder

GALLEY = kitchen_folder("galley")
PROBLEMS = sorted(GALLEY.glob("*.pddl"))


def test_the_galley_has_what_the_issue_asks() -> None:
    kitchen_map = load_kitchen_map(GALLEY / "scene.toml")
    assert len(kitchen_map.openables) >= 2
    assert len(kitchen_map.surfaces) >= 3
    assert len(kitchen_map.boxes) >= 4
    assert not (GALLEY / "domain.pddl").exists()  # it shares the kitchen domain
    assert len(PROBLEMS) >= 3


@pytest.mark.parametrize("problem", PROBLEMS, ids=lambda p: p.stem)
def test_galley_layout_matches_init(problem: Path) -> None:
    task = load_task(problem, default_domain_path())
    with build_kitchen_for_task(task, kitchen_map=load_kitchen_map(GALLEY / "scene.toml")) as kitchen:
        assert abstract_state(kitchen, task.objects) == task.init_atoms
        checker = kitchen.collision_checker()
        assert checker.is_valid(kitchen.home)[0]
        for name in kitchen.boxes:
            bottom = float(np.min(box_corners(kitchen.box(name).base_pose(), kitchen.box_size(name))[:, 2]))
            assert bottom > 0.3


def test_the_swap_needs_the_second_drawer() -> None:
    task = load_task(GALLEY / "problem_swap.pddl", default_domain_path())
    result = plan(task, "bfs")
    assert result.plan is not None
    steps = [action.text for action in result.plan]
    assert len(steps) == 7
    assert "(open left_drawer)" in steps and "(placeIn spam left_drawer)" in steps
    assert ("boxIn", "jam", "right_drawer") in task.init_atoms


def test_drawers_open_independently() -> None:
    task = load_task(GALLEY / "problem_drawers.pddl", default_domain_path())
    with build_kitchen_for_task(task, kitchen_map=load_kitchen_map(GALLEY / "scene.toml")) as kitchen:
        lower, upper = kitchen.opening_limits("left_drawer")
        kitchen.set_opening("left_drawer", upper)
        assert kitchen.is_opened("left_drawer")
        assert not kitchen.is_opened("right_drawer")
        atoms = abstract_state(kitchen, task.objects)
        assert ("opened", "left_drawer") in atoms and ("opened", "right_drawer") not in atoms
        left, right = kitchen.openable_region("left_drawer"), kitchen.openable_region("right_drawer")
        assert left.world_from_region.translation[1] > 0.0 > right.world_from_region.translation[1]
        assert kitchen.collision_checker().is_valid(kitchen.home)[0]
        kitchen.set_opening("left_drawer", lower)
        assert abstract_state(kitchen, task.objects) == task.init_atoms
