"""Confirming what a failed skill blames: the boxes without which the skill finds targets (the
rest put back). A place no sample reaches: tests/refinement/test_failure_feedback.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import (
    FailureKind,
    KitchenScene,
    SkillFailure,
    build_kitchen_for_task,
    load_kitchen_map,
    sample_targets,
)
from kitchen_tamp.kitchen.skills.obstructions import confirm_obstruction, moved_away
from kitchen_tamp.planning import load_task
from kitchen_tamp.shipped_kitchens import kitchen_folder

BENCHMARKS = kitchen_folder("benchmarks")
DOMAIN = BENCHMARKS / "domain.pddl"


class Action:
    """A grounded action as the skills take it."""

    def __init__(self, text: str) -> None:
        self.name, *args = text.split()
        self.args = tuple(args)


def kitchen_in(folder: Path) -> KitchenScene:
    task = load_task(folder / "problem.pddl", DOMAIN)
    return build_kitchen_for_task(task, kitchen_map=load_kitchen_map(folder / "scene.toml", DOMAIN))


def failure_of(kitchen: KitchenScene, action: Action) -> SkillFailure:
    with pytest.raises(SkillFailure) as failed:
        sample_targets(kitchen, action.name, action.args, np.random.default_rng(0))
    return failed.value


def test_boxes_moved_away_are_out_of_the_kitchen_and_come_back() -> None:
    with kitchen_in(BENCHMARKS / "blocked") as kitchen:
        before = kitchen.box("blocker").base_pose()
        with moved_away(kitchen, ["blocker"]):
            assert "blocker" not in kitchen.boxes
            assert kitchen.box("green").base_pose().position[2] > 0.5
        assert "blocker" in kitchen.boxes and kitchen.box("blocker").base_pose() == before


@pytest.mark.slow
@pytest.mark.parametrize(("folder", "action", "blocker"), [
    ("nonmonotonic", "pick red_box table", "red_blocker"),  # the blocked family's: test_failure_feedback
])
def test_an_obstruction_is_confirmed_down_to_the_box_in_the_way(folder: str, action: str,
                                                                blocker: str) -> None:
    with kitchen_in(BENCHMARKS / folder) as kitchen:
        failure = failure_of(kitchen, Action(action))
        assert failure.kind is FailureKind.OBSTRUCTED
        confirmed = confirm_obstruction(kitchen, Action(action), failure, np.random.default_rng(0))
        assert confirmed == (blocker,)
        assert blocker in kitchen.boxes  # back in the kitchen
