"""Packed placements: flush against a region's edges and beside the boxes there, they fit blocks
where uniform draws find no room, say when nothing fits, and hold up under physics."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.cli.final_project import main
from kitchen_tamp.kitchen import KitchenScene, abstract_state, build_kitchen_for_task, load_kitchen_map
from kitchen_tamp.kitchen.skills.packing import box_footprint, packed_placements
from kitchen_tamp.kitchen.skills.parameters import DEFAULT_PARAMETERS
from kitchen_tamp.kitchen.skills.placements import Placement, boxes_overlap, sample_placement
from kitchen_tamp.planning import load_task
from kitchen_tamp.world import Pose
from tests.kitchen.test_placements import DOMAIN, act

COLUMN = Path(__file__).resolve().parent / "problems" / "packed_column"
PARKED = ("block1", "block2", "block3", "block4")
UPRIGHT = (2, -1)
GAP = DEFAULT_PARAMETERS.placement_gap


def column_kitchen() -> KitchenScene:
    """The packed plate with four blocks square to it, two by two against its +x side: the room
    left is a column along its -x edge, a block and a gap wide (and 0.5 mm)."""
    task = load_task(COLUMN / "problem.pddl", DOMAIN)
    return build_kitchen_for_task(task, kitchen_map=load_kitchen_map(COLUMN / "scene.toml", DOMAIN))


def local_x(kitchen: KitchenScene, pose: Pose) -> float:
    return float(kitchen.region("plate").local_point(pose.translation)[0])


def clear_of(pose: Pose, others: list[Pose], size: tuple[float, float, float]) -> bool:
    return not any(boxes_overlap(pose, size, other, size, GAP) for other in others)


def test_packed_poses_fill_the_free_column_where_uniform_draws_find_no_room() -> None:
    with column_kitchen() as kitchen:
        plate, size = kitchen.region("plate"), kitchen.box_size("block5")
        taken = [kitchen.box(b).base_pose() for b in PARKED]
        column_edge = min(local_x(kitchen, pose) for pose in taken) - size[0] / 2.0 - GAP
        rng = np.random.default_rng(0)
        uniform = [sample_placement(plate, size, rng, ((UPRIGHT, 1.0),)) for _ in range(2000)]
        assert not [p for p in uniform if p is not None and clear_of(p.world_from_box, taken, size)]
        added: list[Placement] = []
        while candidates := packed_placements(
            plate, size, [UPRIGHT], [box_footprint(plate, pose, size, GAP) for pose in taken], rng
        ):
            assert all(clear_of(c.world_from_box, taken, size) for c in candidates)
            added.append(candidates[0])
            taken.append(candidates[0].world_from_box)
        assert len(added) == 3  # 25 cm of column holds three blocks 6.5 cm wide, 6 mm apart
        for placement in added:
            assert local_x(kitchen, placement.world_from_box) + size[0] / 2.0 <= column_edge + 1e-6
            assert plate.contains_xy(placement.world_from_box.translation, inset=size[0] / 2.0 - 1e-6)


def test_the_packed_order_is_the_seeds() -> None:
    with column_kitchen() as kitchen:
        plate, size = kitchen.region("plate"), kitchen.box_size("block5")
        footprints = [box_footprint(plate, kitchen.box(b).base_pose(), size, GAP) for b in PARKED]

        def order(seed: int) -> list[tuple[float, ...]]:
            found = packed_placements(plate, size, [UPRIGHT], footprints, np.random.default_rng(seed))
            return [tuple(np.round(p.world_from_box.translation, 6)) for p in found]

        assert order(3) == order(3)
        assert sorted(order(3)) == sorted(order(4)) and order(3) != order(4)


def test_the_place_skill_puts_the_fifth_block_in_the_column() -> None:
    with column_kitchen() as kitchen:
        act(kitchen, "pick block5 table")
        act(kitchen, "place block5 plate")
        assert ("on", "block5", "plate") in abstract_state(kitchen)
        placed, size = kitchen.box("block5").base_pose(), kitchen.box_size("block5")
        assert clear_of(placed, [kitchen.box(b).base_pose() for b in PARKED], size)


@pytest.mark.slow  # a whole planning run with both judges
def test_a_packed_placement_is_verified_by_both_judges(tmp_path: Path) -> None:
    arguments = ["--problem", str(COLUMN / "problem.pddl"), "--domain", str(DOMAIN)]
    assert main(["rrt", *arguments, "--scene", str(COLUMN / "scene.toml"), "--no-video",
                 "--out", str(tmp_path)]) == 0
