"""Placement among the boxes already there: clear of them, on a region beside them, on a box's
top face; "full" (with the boxes that fill it) when nothing fits; grasps blocked by neighbours
name them."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pybullet as p
import pytest

from kitchen_tamp.kitchen import (
    FailureKind,
    KitchenScene,
    SkillFailure,
    SkillTargets,
    UnknownObjectError,
    abstract_state,
    build_kitchen,
    build_kitchen_for_task,
    load_kitchen_map,
    sample_targets,
)
from kitchen_tamp.kitchen.scene.regions import SupportRegion
from kitchen_tamp.kitchen.skills.parameters import DEFAULT_PARAMETERS
from kitchen_tamp.kitchen.skills.placements import boxes_overlap, fits_somewhere
from kitchen_tamp.planning import load_task
from kitchen_tamp.shipped_kitchens import kitchen_folder
from kitchen_tamp.world import Pose

BENCHMARKS = kitchen_folder("benchmarks")
DOMAIN = BENCHMARKS / "domain.pddl"


def kitchen_of(name: str, problem: str = "problem.pddl") -> KitchenScene:
    folder = BENCHMARKS / name
    task = load_task(folder / problem, DOMAIN)
    return build_kitchen_for_task(task, kitchen_map=load_kitchen_map(folder / "scene.toml", DOMAIN))


def act(kitchen: KitchenScene, action: str, seed: int = 0) -> None:
    name, *args = action.split()
    sample_targets(kitchen, name, tuple(args), np.random.default_rng(seed)).apply(kitchen)


def overlapping(kitchen: KitchenScene, box: str) -> list[str]:
    pose, size = kitchen.box(box).base_pose(), kitchen.box_size(box)
    others = (b for b in kitchen.boxes if b != box)
    return [
        b for b in others if boxes_overlap(pose, size, kitchen.box(b).base_pose(), kitchen.box_size(b), 0.0)
    ]


@pytest.fixture
def tray() -> Iterator[KitchenScene]:
    with kitchen_of("kitchen", "problem_radish.pddl") as kitchen:
        yield kitchen


def test_a_box_put_back_among_others_is_clear_of_them(tray: KitchenScene) -> None:
    act(tray, "pick radish tray")
    act(tray, "place radish tray")
    assert {a for a in abstract_state(tray) if a[0] == "on"} == {
        ("on", b, "tray") for b in ("cabbage", "glass", "radish")
    }
    assert overlapping(tray, "radish") == []


def test_a_box_put_on_a_surface_stays_off_its_regions(tray: KitchenScene) -> None:
    act(tray, "pick glass tray")
    act(tray, "place glass worktop")
    assert ("on", "glass", "worktop") in abstract_state(tray)


def test_a_full_region_says_so_and_names_what_fills_it() -> None:
    with kitchen_of("packed") as kitchen:
        plate = kitchen.region("plate")
        # four blocks 1 cm apart around the plate's centre: the strips left at the edges (5.5 cm)
        # are narrower than a block, and the centre is too small even for a block turned 45 degrees
        offset = kitchen.box_size("block1")[0] / 2.0 + 0.005
        for block, (x, y) in zip(("block1", "block2", "block3", "block4"),
                                 ((-1, -1), (-1, 1), (1, -1), (1, 1)), strict=True):
            height = kitchen.box_size(block)[2] / 2 + 0.001
            kitchen.scene.set_base_pose(
                kitchen.box(block), plate.world_from_region @ Pose((x * offset, y * offset, height))
            )
        assert {a for a in abstract_state(kitchen) if a[:1] == ("on",) and a[2] == "plate"} == {
            ("on", f"block{i}", "plate") for i in range(1, 5)
        }
        act(kitchen, "pick block5 table")
        with pytest.raises(SkillFailure) as failed:
            sample_targets(kitchen, "place", ("block5", "plate"), np.random.default_rng(0))
        failure = failed.value
        assert failure.kind is FailureKind.FULL
        assert failure.region == "plate"
        assert set(failure.objects) == {"block1", "block2", "block3", "block4"}
        assert "no reachable collision-free placement in 40 samples" in str(failure)


def test_stacking_puts_the_box_on_the_top_face_of_the_other() -> None:
    with kitchen_of("towers", "problem_sussman.pddl") as kitchen:
        act(kitchen, "unstack c a")
        act(kitchen, "stack c b")
        state = abstract_state(kitchen)
        assert {("on", "c", "b"), ("clear", "c"), ("clear", "a")} <= state and ("clear", "b") not in state
        top = kitchen.box_top("b")
        assert top.contains_xy(kitchen.box("c").base_pose().translation, inset=0.5 * top.half_size[0] - 1e-9)


def test_a_grasp_blocked_by_a_neighbour_names_it() -> None:
    with kitchen_of("blocked") as kitchen:
        with pytest.raises(SkillFailure) as failed:
            sample_targets(kitchen, "pick", ("green", "table"), np.random.default_rng(0))
        assert failed.value.kind is FailureKind.OBSTRUCTED
        assert failed.value.objects[0] == "blocker"
        act(kitchen, "pick blocker table")
        act(kitchen, "place blocker plate")
        act(kitchen, "pick green table")  # with the blocker gone the green block can be taken
        assert ("holding", "green") in abstract_state(kitchen)


def test_processing_needs_the_box_on_the_place() -> None:
    with kitchen_of("kitchen", "problem_radish.pddl") as kitchen:
        with pytest.raises(SkillFailure, match="radish rests on tray, not on sink") as failed:
            sample_targets(kitchen, "wash", ("radish", "sink"), np.random.default_rng(0))
        assert failed.value.kind is FailureKind.PRECONDITION
        act(kitchen, "pick radish tray")
        act(kitchen, "place radish sink")
        targets = sample_targets(kitchen, "wash", ("radish", "sink"), np.random.default_rng(0))
        assert np.array_equal(targets.goal_configuration, kitchen.arm_configuration())
        assert [s.name for s in targets.segments] == ["process"]


def test_the_seed_kitchen_still_refuses_a_box_of_the_wrong_type() -> None:
    objects = {"stove": "surface", "countertop": "surface", "sugar": "box"}
    init = {("boxOn", "sugar", "stove"), ("surfClear", "countertop"), ("armClear",)}
    with (
        build_kitchen(objects, init) as kitchen,
        pytest.raises(UnknownObjectError, match="placeOn needs a surface here, sugar is a box"),
    ):
        sample_targets(kitchen, "placeOn", ("sugar", "sugar"), np.random.default_rng(0))


def test_a_box_fits_a_region_in_some_orientation_or_in_none() -> None:
    drawer = SupportRegion("drawer", Pose((0.0, 0.0, 0.0)), (0.17, 0.17), 0.2)
    assert fits_somewhere(drawer, (0.10, 0.05, 0.085))  # lying flat
    assert fits_somewhere(drawer, (0.06, 0.06, 0.50))  # only standing up
    assert fits_somewhere(drawer, (0.40, 0.40, 0.07))  # only on its edge, across the diagonal
    assert not fits_somewhere(drawer, (0.45, 0.45, 0.07))  # (0.45 + 0.07) / sqrt(2) > 0.34
    assert fits_somewhere(drawer, (0.45, 0.45, 0.07), centre_inset=0.085)  # stacked: its centre over it


def test_a_box_too_large_for_the_region_is_named_as_such(
    tray: KitchenScene, monkeypatch: pytest.MonkeyPatch
) -> None:
    act(tray, "pick glass tray")
    real_size = tray.box_size
    monkeypatch.setattr(tray, "box_size", lambda box: (0.5, 0.5, 0.5) if box == "glass" else real_size(box))
    with pytest.raises(SkillFailure) as failed:
        sample_targets(tray, "place", ("glass", "sink"), np.random.default_rng(0))
    assert failed.value.kind is FailureKind.TOO_LARGE and failed.value.region == "sink"
    assert "glass fits sink in no orientation" in str(failed.value)


def test_a_box_placed_among_parked_boxes_keeps_the_placement_gap_from_each() -> None:
    gap = DEFAULT_PARAMETERS.placement_gap
    with kitchen_of("sort_clutter") as kitchen:
        region = kitchen.region("blue_region")
        parked = ("clutter1", "clutter2", "clutter4")
        size = kitchen.box_size("clutter3")
        for i, box in enumerate(parked):  # a row across the region, a box's width apart
            height = kitchen.box_size(box)[2] / 2 + 0.001
            at = region.world_from_region @ Pose(((i - 1) * 2 * size[0], 0.0, height))
            kitchen.scene.set_base_pose(kitchen.box(box), at)
        last = kitchen.box("clutter4").base_pose()
        assert boxes_overlap(last @ Pose((0.0, size[1] + 0.004, 0.0)), size, last, size, gap)  # 4 mm apart
        act(kitchen, "pick clutter3 table")
        holding = kitchen.scene.save_state()
        for seed in range(3):
            kitchen.scene.restore_state(holding)
            act(kitchen, "place clutter3 blue_region", seed)
            placed = kitchen.box("clutter3").base_pose()
            assert ("on", "clutter3", "blue_region") in abstract_state(kitchen)
            assert not [b for b in parked
                        if boxes_overlap(placed, size, kitchen.box(b).base_pose(), size, gap - 1e-6)]


def robot_distance_to_boxes(kitchen: KitchenScene, targets: SkillTargets, besides: str) -> float:
    """Smallest distance (m, PyBullet's closest points) of the robot, along the targets' segments,
    to every box but ``besides``, up to 2 cm."""
    robot, nearest = kitchen.robot, 0.02
    with kitchen.scene.preserved():
        for segment in targets.segments:
            for q, width in zip(segment.configurations, segment.gripper_widths, strict=True):
                robot.set_configuration(q)
                robot.set_gripper_width(float(width))
                for name, body in kitchen.boxes.items():
                    if name != besides:
                        closest = p.getClosestPoints(
                            robot.body.uid, body.uid, nearest, physicsClientId=body.client
                        )
                        nearest = min([nearest, *(float(point[8]) for point in closest)])
    return nearest


@pytest.mark.parametrize("seed", [5, 7])
def test_the_hand_keeps_its_clearance_from_the_boxes_beside_the_one_it_handles(seed: int) -> None:
    """Three boxes parked a box's width apart: picking a box beside them and placing it among
    them, the hand stays ``neighbour_clearance`` from each. (Without it, these seeds pass a
    neighbour 1.3 mm away picking, 1.9 mm placing: close enough to touch under physics.)"""
    clearance = DEFAULT_PARAMETERS.neighbour_clearance
    with kitchen_of("sort_clutter") as kitchen:
        region = kitchen.region("blue_region")
        size = kitchen.box_size("clutter3")
        for i, box in enumerate(("clutter1", "clutter2", "clutter4")):
            height = kitchen.box_size(box)[2] / 2 + 0.001
            at = region.world_from_region @ Pose(((i - 1) * 2 * size[0], 0.0, height))
            kitchen.scene.set_base_pose(kitchen.box(box), at)
        pick = sample_targets(kitchen, "pick", ("clutter3", "table"), np.random.default_rng(seed))
        assert robot_distance_to_boxes(kitchen, pick, "clutter3") >= clearance - 1e-4
        pick.apply(kitchen)
        place = sample_targets(kitchen, "place", ("clutter3", "blue_region"), np.random.default_rng(seed))
        assert robot_distance_to_boxes(kitchen, place, "clutter3") >= clearance - 1e-4
