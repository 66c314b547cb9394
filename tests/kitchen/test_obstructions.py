"""Confirming what a failed skill blames: the fewest named boxes without which the skill finds
targets (the rest put back), and a place no sample reaches with every other box moved out."""

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
from kitchen_tamp.kitchen.skills.obstructions import confirm_obstruction, confirm_unreachable, moved_away
from kitchen_tamp.planning import load_task
from kitchen_tamp.shipped_kitchens import kitchen_folder

BENCHMARKS = kitchen_folder("benchmarks")
DOMAIN = BENCHMARKS / "domain.pddl"
FAR_PLATE = Path(__file__).resolve().parent / "problems" / "far_plate"


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
    ("blocked", "pick green table", "blocker"),
    ("nonmonotonic", "pick red_box table", "red_blocker"),
])
def test_an_obstruction_is_confirmed_down_to_the_box_in_the_way(folder: str, action: str,
                                                                blocker: str) -> None:
    with kitchen_in(BENCHMARKS / folder) as kitchen:
        failure = failure_of(kitchen, Action(action))
        assert failure.kind is FailureKind.OBSTRUCTED
        confirmed = confirm_obstruction(kitchen, Action(action), failure, np.random.default_rng(0))
        assert confirmed == (blocker,)
        assert blocker in kitchen.boxes  # back in the kitchen


@pytest.mark.slow
def test_names_whose_removal_does_not_help_are_not_confirmed() -> None:
    with kitchen_in(FAR_PLATE) as kitchen:
        far = Action("pick green table")
        sample_targets(kitchen, far.name, far.args, np.random.default_rng(0)).apply(kitchen)
        failure = failure_of(kitchen, Action("place green far_plate"))
        assert failure.kind is FailureKind.UNREACHABLE
        blamed = SkillFailure(failure.action, failure.detail, FailureKind.OBSTRUCTED, ("green",), "far_plate")
        assert confirm_obstruction(kitchen, Action("place green far_plate"), blamed,
                                   np.random.default_rng(0)) == ()  # its own box is never blamed


@pytest.mark.slow
def test_a_place_out_of_reach_is_confirmed_and_one_in_reach_is_not() -> None:
    with kitchen_in(FAR_PLATE) as kitchen:
        pick = Action("pick green table")
        sample_targets(kitchen, pick.name, pick.args, np.random.default_rng(0)).apply(kitchen)
        assert confirm_unreachable(kitchen, Action("place green far_plate"), np.random.default_rng(0))
        assert not confirm_unreachable(kitchen, Action("place green plate"), np.random.default_rng(0))
        assert kitchen.held_box() == "green"
