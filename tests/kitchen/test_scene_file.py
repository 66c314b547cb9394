"""The scene file's schema: every kind of mistake gets one line naming the file, the key and
what is wrong, and the command lines exit 2 on it."""

from __future__ import annotations

import copy
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from kitchen_tamp.cli.final_project import main as final_project_main
from kitchen_tamp.kitchen.__main__ import main as kitchen_main
from kitchen_tamp.kitchen.scene.spec_reader import SceneFileError, parse_scene, read_scene
from kitchen_tamp.shipped_kitchens import default_scene_path
from tests.kitchen.conftest import PROBLEMS, REPO

SCENE = Path("my_kitchen.toml")


def default_data() -> dict[str, Any]:
    return tomllib.loads(default_scene_path().read_text())


def drop_height(data: dict[str, Any]) -> None:
    del data["surfaces"][1]["height"]


def negative_box(data: dict[str, Any]) -> None:
    data["boxes"][0]["size"] = [0.09, -0.04, 0.175]


def huge_box(data: dict[str, Any]) -> None:
    data["boxes"][1]["size"] = [0.50, 0.45, 0.10]


def second_drawer_overlapping(data: dict[str, Any]) -> None:
    twin = copy.deepcopy(data["drawers"][0])
    twin["name"] = "lower_drawer"
    twin["y"] = data["drawers"][0]["y"] + 0.20
    data["drawers"].append(twin)


def name_twice(data: dict[str, Any]) -> None:
    data["boxes"][2]["name"] = "stove"


def misspelt_key(data: dict[str, Any]) -> None:
    data["counter"]["heigth"] = data["counter"].pop("height")


def extra_key(data: dict[str, Any]) -> None:
    data["boxes"][0]["flavour"] = "sweet"


def surface_off_the_edge(data: dict[str, Any]) -> None:
    data["surfaces"][0]["extent"] = [[0.48, 0.74], [0.50, 0.80]]


def bad_name(data: dict[str, Any]) -> None:
    data["boxes"][1]["name"] = "spam can"


def missing_depth(data: dict[str, Any]) -> None:
    del data["counter"]["depth"]


def counter_through_the_mount(data: dict[str, Any]) -> None:
    data["counter"]["front"] = 0.05  # the mount reaches to x = 0.11


def table_where_the_drawer_opens(data: dict[str, Any]) -> None:
    data["surfaces"].append({"name": "table", "extent": [[-0.05, 0.30], [-0.45, -0.15]], "height": 0.40,
                             "colour": [0.4, 0.5, 0.6, 1.0]})


def drawer_into_the_mount(data: dict[str, Any]) -> None:
    data["drawers"][0]["y"] = -0.10
    data["drawers"][0]["size"] = [0.40, 0.20, 0.20]
    data["drawers"][0]["travel"] = 0.38


def drawer_too_wide(data: dict[str, Any]) -> None:
    data["drawers"][0]["size"] = [0.34, 1.40, 0.20]


MISTAKES: dict[str, tuple[Callable[[dict[str, Any]], None], str, str]] = {
    "missing key": (drop_height, "surfaces.countertop", "missing key 'height'"),
    "negative size": (negative_box, "boxes.sugar.size", "must be positive, got -0.04"),
    "box larger than its place": (huge_box, "boxes.spam.size", "larger than every surface and drawer"),
    "drawers overlapping": (
        second_drawer_overlapping, "drawers.lower_drawer.y", "its cavity overlaps drawer 'drawer'"
    ),
    "name used twice": (name_twice, "boxes.stove.name", "name 'stove' used twice (also in surfaces)"),
    "misspelt key": (misspelt_key, "counter", "missing key 'height' (is 'heigth' a misspelling?)"),
    "unknown key": (extra_key, "boxes.sugar.flavour", "unknown key"),
    "not a PDDL name": (bad_name, "boxes[1].name", "'spam can' is not a PDDL name"),
    "surface half off the counter": (surface_off_the_edge, "surfaces.stove.extent", "partly on the counter"),
    "missing key, no misspelling near": (missing_depth, "counter", "missing key 'depth'"),
    "counter through the mount": (counter_through_the_mount, "counter.front", "cuts through the robot's"),
    "floor table in the drawer's way": (
        table_where_the_drawer_opens, "drawers.drawer.travel", "slides into surface 'table'"
    ),
    "drawer into the mount": (drawer_into_the_mount, "drawers.drawer.travel", "slides into the robot's"),
    "drawer wider than the counter": (drawer_too_wide, "drawers.drawer.size", "does not fit the counter's"),
}


@pytest.mark.parametrize("mistake", sorted(MISTAKES))
def test_each_mistake_names_file_key_and_problem(mistake: str) -> None:
    change, key, detail = MISTAKES[mistake]
    data = default_data()
    change(data)
    with pytest.raises(SceneFileError) as raised:
        parse_scene(SCENE, data)
    message = str(raised.value)
    assert message == f"{SCENE}: {key}: {detail}" or (
        message.startswith(f"{SCENE}: {key}: ") and detail in message
    ), message
    assert "\n" not in message
    assert raised.value.key == key
    if mistake == "missing key, no misspelling near":
        assert message.endswith("missing key 'depth'"), message  # 'width' is present: no hint

def test_the_default_scene_reads_cleanly() -> None:
    spec = read_scene(default_scene_path())
    assert [s.name for s in spec.surfaces] == ["stove", "countertop"]
    assert [d.name for d in spec.drawers] == ["drawer"]
    assert [b.name for b in spec.boxes] == ["sugar", "spam", "baguette"]


def test_malformed_toml_names_the_line(tmp_path: Path) -> None:
    scene = tmp_path / "broken.toml"
    scene.write_text('name = "x"\n[counter\n')
    with pytest.raises(SceneFileError, match=r"broken\.toml: not valid TOML: .*line 2"):
        read_scene(scene)


def _write_bad_scene(tmp_path: Path) -> Path:
    text = default_scene_path().read_text()
    text = text.replace("size = [0.09, 0.04, 0.175]", "size = [0.09, -0.04, 0.175]")
    assert text != default_scene_path().read_text()
    scene = tmp_path / "bad_scene.toml"
    scene.write_text(text)
    return scene


@pytest.mark.parametrize("program", ["show", "rrt", "optimizes"])
def test_command_lines_exit_2_on_a_bad_scene(
    tmp_path: Path, program: str, capsys: pytest.CaptureFixture[str]
) -> None:
    scene = _write_bad_scene(tmp_path)
    if program == "show":
        code = kitchen_main(["show", "--scene", str(scene), "--out", str(tmp_path / "x.png")])
    else:
        arguments = [program, "--scene", str(scene), "--out", str(tmp_path / "run"), "--no-video"]
        code = final_project_main(arguments)
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert err == f"error: {scene}: boxes.sugar.size: must be positive, got -0.04"
    assert not (tmp_path / "run").exists()


@pytest.mark.parametrize(
    ("problem", "names"),
    [("unknown_object.pddl", "'soup'"), ("wrongly_typed_object.pddl", "'sugar': it is a box")],
)
def test_problem_objects_must_match_the_scene(
    tmp_path: Path, problem: str, names: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code = kitchen_main(
        ["show", "--problem", str(PROBLEMS / problem), "--domain", str(REPO / "pddl" / "domain.pddl"),
         "--out", str(tmp_path / "x.png")]
    )
    err = capsys.readouterr().err
    assert code == 2
    assert names in err and str(default_scene_path()) in err
    assert err.count("\n") == 1
