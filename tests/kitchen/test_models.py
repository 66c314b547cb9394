"""The kitchen's models come from its scene file and cannot drift from it: the files a built
kitchen loads are the generator's output, the copies in models/ are the default kitchen's,
the default kitchen is today's, and drawers (none, one, two) each get their own cavity."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import pytest

from kitchen_tamp.kitchen import abstract_state, build_kitchen_for_task, default_kitchen_map, load_kitchen_map
from kitchen_tamp.kitchen.scene.models import BoxPart, cabinet_parts, model_files, model_texts
from kitchen_tamp.kitchen.scene.spec import KitchenSpec
from kitchen_tamp.kitchen.scene.spec_reader import parse_scene, read_scene
from kitchen_tamp.planning import load_task
from kitchen_tamp.shipped_kitchens import (
    default_domain_path,
    default_scene_path,
    kitchen_folder,
    shipped_kitchens,
)
from tests.kitchen.conftest import REPO


def test_models_folder_holds_the_default_kitchens_models() -> None:
    texts = model_texts(read_scene(default_scene_path()))
    assert sorted(texts) == sorted(p.name for p in (REPO / "models").glob("*.urdf"))
    for file_name, text in texts.items():
        assert (REPO / "models" / file_name).read_text() == text, (
            f"models/{file_name} is stale: run python models/generate_models.py"
        )


@pytest.mark.parametrize("kitchen", shipped_kitchens())
def test_loaded_models_are_the_scene_files_models(kitchen: str) -> None:
    spec = read_scene(kitchen_folder(kitchen) / "scene.toml")
    texts = model_texts(spec)
    files = model_files(spec)
    assert files.kitchen.read_text() == texts["kitchen.urdf"]
    for box, path in files.boxes.items():
        assert path.read_text() == texts[f"{box}.urdf"]


def test_models_are_written_to_the_cache_not_the_working_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    files = model_files(read_scene(default_scene_path()))
    assert files.kitchen.is_relative_to(tmp_path / "cache")
    assert list(work.iterdir()) == []


def test_the_default_kitchen_is_todays() -> None:
    """The numbers of the kitchen before it became data (models/generate_models.py's constants)."""
    spec = read_scene(default_scene_path())
    assert (spec.counter.front, spec.counter.depth, spec.counter.width, spec.counter.height) == (
        0.45, 0.60, 1.30, 0.60,
    )
    stove, countertop = spec.surfaces
    assert (stove.x_range, stove.y_range, stove.height, stove.burners) == (
        (0.48, 0.74), (0.06, 0.40), 0.612, True,
    )
    assert (countertop.x_range, countertop.y_range, countertop.height) == (
        (0.48, 0.74), (-0.40, -0.06), 0.604,
    )
    (drawer,) = spec.drawers
    assert (drawer.inner, drawer.y, drawer.travel, drawer.wall, drawer.gap) == (
        (0.34, 0.34, 0.20), -0.24, 0.28, 0.015, 0.01,
    )
    assert {b.name: b.size for b in spec.boxes} == {
        "sugar": (0.09, 0.04, 0.175), "spam": (0.10, 0.05, 0.085), "baguette": (0.06, 0.06, 0.50),
    }
    kitchen_map = default_kitchen_map()
    assert dict(kitchen_map.openables)["drawer"].joint == "drawer_joint"
    assert set(kitchen_map.surfaces) == {"stove", "countertop"}
    # The cabinet is still the hand-cut one: slab, left and right of the cavity, below and behind it.
    assert len(cabinet_parts(spec)) == 5


def _spec_with_drawers(drawers: list[dict[str, Any]]) -> KitchenSpec:
    data = tomllib.loads(default_scene_path().read_text())
    data["drawers"] = drawers
    return parse_scene(Path("test.toml"), data)


def _boxes_intersect(a: BoxPart, low: tuple[float, ...], high: tuple[float, ...]) -> bool:
    return all(
        a.center[i] - a.size[i] / 2 < high[i] - 1e-9 and low[i] + 1e-9 < a.center[i] + a.size[i] / 2
        for i in range(3)
    )


@pytest.mark.parametrize("count", [0, 1, 2])
def test_each_drawer_has_its_own_cavity(count: int) -> None:
    template = tomllib.loads(default_scene_path().read_text())["drawers"][0]
    drawers = [dict(template, name=f"drawer{i}", y=-0.24 + 0.45 * i) for i in range(count)]
    spec = _spec_with_drawers(drawers)
    parts = [p for p in cabinet_parts(spec) if isinstance(p, BoxPart)]
    counter = spec.counter
    volume = sum(p.size[0] * p.size[1] * p.size[2] for p in parts)
    cavities = 0.0
    for drawer in spec.drawers:
        length, _, height = drawer.outer
        low_y, high_y = drawer.cavity_y
        top = counter.slab_bottom
        low = (counter.front, low_y, top - height - 2 * drawer.gap)
        high = (counter.front + length + drawer.gap, high_y, top)
        assert not any(_boxes_intersect(p, low, high) for p in parts), drawer.name
        cavities += (high[0] - low[0]) * (high[1] - low[1]) * (high[2] - low[2])
    # The parts fill the cabinet exactly, less the cavities: no gaps, no overlaps.
    assert volume == pytest.approx(counter.depth * counter.width * counter.height - cavities)


def test_a_kitchen_without_drawers_is_laid_out(tmp_path: Path) -> None:
    text = default_scene_path().read_text()
    scene = tmp_path / "no_drawers.toml"
    scene.write_text(text[: text.index("[[drawers]]")] + text[text.index("[[boxes]]") :])
    problem = tmp_path / "problem.pddl"
    problem.write_text(
        "(define (problem no-drawer) (:domain kitchen)"
        " (:objects stove countertop - surface sugar - box)"
        " (:init (boxOn sugar stove) (surfClear countertop) (armClear))"
        " (:goal (boxOn sugar countertop)))"
    )
    kitchen_map = load_kitchen_map(scene)
    assert dict(kitchen_map.openables) == {}
    task = load_task(problem, default_domain_path())
    with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
        assert abstract_state(kitchen, task.objects) == task.init_atoms
        assert kitchen.kitchen.link_names == ("cabinet", "robot_mount", "stove", "countertop")
