"""The sphere data the package ships: a kitchen's first sphere model computes nothing (every
covering and pair table it needs is shipped), and the shipped files are what the generator
makes from nothing."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import kitchen_tamp.motion.geometry.spheres.pair_tables as pair_tables
import kitchen_tamp.motion.geometry.spheres.scene as scene
from kitchen_tamp.cli.shipped_spheres import TABLE_MARGINS, differences, generate
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.scene.choice import choose_scene
from kitchen_tamp.motion.geometry.spheres import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.covering import DEFAULT_COVERING_TOLERANCE
from kitchen_tamp.motion.geometry.spheres.stored_spheres import read_shipped
from kitchen_tamp.motion.geometry.spheres.tight_covering import TIGHT_COVERING_TOLERANCE
from kitchen_tamp.motion.geometry.urdf import read_urdf
from kitchen_tamp.planning import load_task
from kitchen_tamp.world import describe_collision_checker


def _refuse(*_: object, **__: object) -> None:
    raise AssertionError("computed although it is shipped")


def test_the_default_kitchen_finds_every_covering_and_table_shipped(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))  # an empty user cache
    choice = choose_scene("problem.pddl")
    kitchen_map = choice.kitchen_map()
    scene._covered_shape.cache_clear()
    pair_tables._stored_cells.cache_clear()
    monkeypatch.setattr(scene, "cover_with_spheres", _refuse)
    monkeypatch.setattr(scene, "cover_tightly", _refuse)
    monkeypatch.setattr(pair_tables, "_prove_cells", _refuse)
    try:
        task = load_task(choice.problem, choice.domain)
        with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
            spam = read_urdf(str(kitchen_map.boxes["spam"].urdf)).collisions[0]
            for width in (kitchen.robot.max_gripper_width, float(min(spam.size))):
                kitchen.robot.set_gripper_width(width)
                description = describe_collision_checker(kitchen.collision_checker())
                for margin in TABLE_MARGINS:
                    checker = SphereCollisionChecker(description, margin=margin)
                    assert checker.is_valid(np.atleast_2d(kitchen.arm_configuration())).all()
        for box in kitchen_map.boxes.values():
            scene._covered_shape(str(box.urdf), 0, DEFAULT_COVERING_TOLERANCE, False)
            scene._covered_shape(str(box.urdf), 0, TIGHT_COVERING_TOLERANCE, True)
    finally:
        scene._covered_shape.cache_clear()
        pair_tables._stored_cells.cache_clear()
    assert not (tmp_path / "kitchen_tamp" / "spheres").exists()  # nothing needed storing


@pytest.mark.slow
def test_the_shipped_spheres_are_what_the_generator_makes() -> None:
    """Covers the Panda's meshes and the shipped kitchens' boxes and proves the pair tables from
    nothing (a couple of minutes of one core), then compares with the shipped files."""
    assert differences(generate(), read_shipped()) == []
