"""Regions, stacks and conditions: the scene file's keys for them, the layout of several boxes on
one support, and Ψ of the built scenes in the regions domain (derived from geometry only)."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.cli.final_project import main as final_project_main
from kitchen_tamp.kitchen import (
    InitialStateMismatchError,
    KitchenScene,
    SceneFileError,
    UnsupportedInitialStateError,
    abstract_state,
    apply_condition_effects,
    build_kitchen,
    build_kitchen_for_task,
    default_kitchen_map,
    load_kitchen_map,
)
from kitchen_tamp.kitchen.abstraction import rests_on
from kitchen_tamp.kitchen.scene.kitchen_map import KitchenMap
from kitchen_tamp.kitchen.scene.models import CABINET_LINK
from kitchen_tamp.kitchen.scene.regions import box_corners
from kitchen_tamp.kitchen.scene.spec_reader import parse_scene
from kitchen_tamp.planning import Atom, Task, load_task
from kitchen_tamp.shipped_kitchens import default_scene_path, kitchen_folder
from kitchen_tamp.world import Pose

BENCHMARKS = kitchen_folder("benchmarks")
DOMAIN = BENCHMARKS / "domain.pddl"


def family(name: str) -> tuple[Path, KitchenMap]:
    folder = BENCHMARKS / name
    return folder, load_kitchen_map(folder / "scene.toml", DOMAIN)


def built(name: str, problem: str = "problem.pddl") -> tuple[Task, KitchenScene]:
    folder, kitchen_map = family(name)
    task = load_task(folder / problem, DOMAIN)
    return task, build_kitchen_for_task(task, kitchen_map=kitchen_map)


def test_several_items_rest_on_one_region_and_psi_says_so() -> None:
    task, kitchen = built("kitchen")
    with kitchen:
        state = abstract_state(kitchen, task.objects)
        assert state == task.init_atoms
        items = ("cabbage", "glass", "radish")
        assert {a for a in state if a[0] == "on"} == {("on", b, "tray") for b in items}
        assert all(rests_on(kitchen, box, kitchen.region("tray")) for box in ("cabbage", "glass", "radish"))


def test_a_box_on_a_plate_is_on_the_plate_not_on_the_table() -> None:
    task, kitchen = built("nonmonotonic")
    with kitchen:
        plate = kitchen.region("red_plate")
        size = kitchen.box_size("red_box")
        kitchen.scene.set_base_pose(
            kitchen.box("red_box"), plate.world_from_region @ Pose((0.0, 0.0, size[2] / 2 + 0.001))
        )
        state = abstract_state(kitchen, task.objects)
        assert ("on", "red_box", "red_plate") in state
        assert ("on", "red_box", "table") not in state
        # half off the plate's face (its centre off it) it rests on neither: it does not stand
        kitchen.scene.set_base_pose(
            kitchen.box("red_box"), plate.world_from_region @ Pose((0.0, 0.16, size[2] / 2 + 0.001))
        )
        assert not {a for a in abstract_state(kitchen, task.objects) if a[:2] == ("on", "red_box")}


def test_a_stack_is_on_the_box_below_and_only_the_top_is_clear() -> None:
    task, kitchen = built("towers", "problem_reversal.pddl")
    with kitchen:
        state = abstract_state(kitchen, task.objects)
        assert state == task.init_atoms
        assert {("on", "a", "b"), ("on", "b", "c"), ("on", "c", "table"), ("clear", "a")} <= state
        assert ("clear", "b") not in state and ("clear", "c") not in state
        bottom_a = float(np.min(box_corners(kitchen.box("a").base_pose(), kitchen.box_size("a"))[:, 2]))
        assert bottom_a == pytest.approx(kitchen.box_top("b").top_z + 0.001, abs=1e-6)
        # lifted off, b is clear and a rests on nothing
        kitchen.scene.set_base_pose(kitchen.box("a"), kitchen.box("a").base_pose().translated((0, 0, 0.05)))
        state = abstract_state(kitchen, task.objects)
        assert ("clear", "b") in state and not {x for x in state if x[:2] == ("on", "a")}


def test_conditions_come_from_init_and_from_the_effects_of_actions() -> None:
    folder, kitchen_map = family("kitchen")
    task = load_task(folder / "problem_radish.pddl", DOMAIN)
    init: frozenset[Atom] = task.init_atoms | {("clean", "glass")}
    with build_kitchen(task.objects, init, kitchen_map=kitchen_map) as kitchen:
        assert abstract_state(kitchen, task.objects) == init
        apply_condition_effects(kitchen, [("cooked", "glass"), ("on", "glass", "hob")], [("clean", "glass")])
        state = abstract_state(kitchen, task.objects)
        assert ("cooked", "glass") in state and ("clean", "glass") not in state
        assert ("on", "glass", "hob") not in state  # geometry's, not the effects'


def test_the_init_is_checked_against_psi_of_the_scene() -> None:
    folder, kitchen_map = family("towers")
    task = load_task(folder / "problem_sussman.pddl", DOMAIN)
    with pytest.raises(InitialStateMismatchError, match=r"in the scene but not in :init: \(clear a\)"):
        build_kitchen(task.objects, task.init_atoms - {("on", "c", "a")} | {("on", "c", "table")},
                      kitchen_map=kitchen_map).close()


def test_boxes_without_a_start_are_laid_out_in_rows() -> None:
    folder, _ = family("packed")
    task = load_task(folder / "problem.pddl", DOMAIN)
    on_plate = {a for a in task.init_atoms if a[0] != "on"}
    on_plate |= {("on", f"block{i}", "plate") for i in range(1, 6)}
    data = tomllib.loads((folder / "scene.toml").read_text())
    for box in data["boxes"]:
        del box["at"]
    spec_map = _map_of(folder / "scene.toml", data)
    with build_kitchen(task.objects, on_plate, kitchen_map=spec_map) as kitchen:
        assert abstract_state(kitchen, task.objects) == on_plate
        across = {round(float(kitchen.box(f"block{i}").base_pose().translation[1]), 3) for i in range(1, 6)}
        assert len(across) == 2  # five 6.5 cm blocks do not fit one row of a 25 cm plate: two rows


def _map_of(path: Path, data: dict[str, Any]) -> KitchenMap:
    from kitchen_tamp.kitchen.binding_reader import read_binding
    from kitchen_tamp.kitchen.scene.kitchen_map import kitchen_map_of

    return kitchen_map_of(parse_scene(path, data), read_binding(DOMAIN))


def test_a_start_off_the_support_init_names_is_refused_naming_the_box() -> None:
    folder, kitchen_map = family("nonmonotonic")
    task = load_task(folder / "problem.pddl", DOMAIN)
    init = task.init_atoms - {("on", "red_box", "table")} | {("on", "red_box", "red_plate")}
    with pytest.raises(UnsupportedInitialStateError, match=r"box 'red_box' starts at \(0.66, -0.09\)"):
        build_kitchen(task.objects, init, kitchen_map=kitchen_map).close()


OPEN_DRAWER_OBJECTS = {"stove": "surface", "countertop": "surface", "drawer": "openable", "sugar": "box",
                       "spam": "box"}
OPEN_DRAWER_INIT: frozenset[Atom] = frozenset({
    ("boxIn", "sugar", "drawer"), ("boxIn", "spam", "drawer"), ("opened", "drawer"),
    ("surfClear", "stove"), ("surfClear", "countertop"), ("armClear",),
})


def test_boxes_in_an_open_drawer_start_out_from_under_the_slab() -> None:
    with build_kitchen(OPEN_DRAWER_OBJECTS, OPEN_DRAWER_INIT) as kitchen:
        front = float(kitchen.kitchen.aabb(CABINET_LINK)[0][0])
        for box in ("sugar", "spam"):
            corners = box_corners(kitchen.box(box).base_pose(), kitchen.box_size(box))
            assert float(np.max(corners[:, 0])) < front


def test_a_box_too_big_for_the_open_part_of_a_drawer_is_refused_naming_it(tmp_path: Path) -> None:
    data = tomllib.loads(default_scene_path().read_text())
    data["drawers"][0]["travel"] = 0.12  # the drawer opens 12 cm: 8.5 cm of its floor comes out
    kitchen_map = _default_domain_map(tmp_path, data)
    init = {("boxIn", "spam", "drawer"), ("opened", "drawer"), ("surfClear", "stove"),
            ("surfClear", "countertop"), ("armClear",)}
    objects = {"stove": "surface", "countertop": "surface", "drawer": "openable", "spam": "box"}
    with pytest.raises(UnsupportedInitialStateError, match=r"spam.*do not fit side by side in 'drawer'"):
        build_kitchen(objects, init, kitchen_map=kitchen_map).close()
    closed = init - {("opened", "drawer")}
    with build_kitchen(objects, closed, kitchen_map=kitchen_map) as kitchen:  # closed: its whole floor
        assert abstract_state(kitchen) == frozenset(closed)


def _default_domain_map(tmp_path: Path, data: dict[str, Any]) -> KitchenMap:
    from kitchen_tamp.kitchen.scene.kitchen_map import kitchen_map_of

    return kitchen_map_of(parse_scene(tmp_path / "scene.toml", data), default_kitchen_map().binding)


def _regions_data() -> dict[str, Any]:
    return tomllib.loads((BENCHMARKS / "kitchen" / "scene.toml").read_text())


SCENE_MISTAKES = {
    "region larger than its surface": (
        lambda d: d["regions"][0].update(extent=[[0.40, 0.80], [-0.40, -0.26]]),
        "regions.plate.extent",
        "the region (0.4 x 0.14 m) is larger than its surface 'worktop' (0.3 x 0.84 m)",
    ),
    "region off its surface": (
        lambda d: d["regions"][0].update(extent=[[0.70, 0.80], [-0.40, -0.26]]),
        "regions.plate.extent", "lies partly off its surface 'worktop'",
    ),
    "regions overlapping": (
        lambda d: d["regions"][1].update(extent=[[0.50, 0.66], [-0.30, -0.08]]),
        "regions.hob.extent", "overlaps region 'plate'",
    ),
    "region on no surface": (
        lambda d: d["regions"][0].update(surface="shelf"), "regions.plate.surface",
        "no surface 'shelf' (surfaces: worktop)",
    ),
    "region named like a box": (
        lambda d: d["regions"][0].update(name="glass"), "regions.glass.name",
        "name 'glass' used twice (also in boxes)",
    ),
    "turn without a start": (
        lambda d: (d["boxes"][0].pop("at"), d["boxes"][0].update(yaw=30)), "boxes.cabbage.yaw",
        "a turn needs a start position",
    ),
    "obstacle half on a region": (
        lambda d: d.setdefault("obstacles", []).append(
            {"name": "wall", "extent": [[0.60, 0.62], [0.10, 0.30]], "height": 0.70}
        ),
        "obstacles.wall.extent", "overlaps region 'sink'",
    ),
}


@pytest.mark.parametrize("mistake", sorted(SCENE_MISTAKES))
def test_a_bad_region_names_file_key_and_problem(mistake: str) -> None:
    change, key, detail = SCENE_MISTAKES[mistake]
    data = _regions_data()
    change(data)
    with pytest.raises(SceneFileError) as raised:
        parse_scene(Path("my.toml"), data)
    assert raised.value.key == key
    assert str(raised.value).startswith(f"my.toml: {key}: ") and detail in str(raised.value)


def test_a_region_larger_than_its_surface_exits_2_with_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = (BENCHMARKS / "kitchen" / "scene.toml").read_text()
    scene = tmp_path / "scene.toml"
    plate, too_large = "extent = [[0.50, 0.70], [-0.40, -0.26]]", "extent = [[0.40, 0.80], [-0.40, -0.26]]"
    scene.write_text(text.replace(plate, too_large))
    problem = BENCHMARKS / "kitchen" / "problem.pddl"
    arguments = ["rrt", "--problem", str(problem), "--scene", str(scene), "--no-video",
                 "--out", str(tmp_path / "run")]
    assert final_project_main(arguments) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "regions.plate.extent" in err[0] and "larger than its surface" in err[0]
