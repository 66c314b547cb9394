"""``python -m kitchen_tamp.cli.shipped_spheres [--check]``: make the sphere data the package ships.

Generates, from nothing (an empty cache, the shipped files ignored), what
`kitchen_tamp.motion.geometry.spheres.stored_spheres` ships: both coverings of
every collision shape of the robot and of every box of the kitchens in
``SHIPPED_KITCHENS``, and the robot's pair tables at each margin in
``TABLE_MARGINS`` (the margins refinement plans with), with the hand open and
holding each of those boxes (a table between link 5 and a finger is proved for
one opening of the hand). Without ``--check`` it
writes them into the package; with it, it says whether they equal what is shipped
(exit 1 when not). Covering the Panda's meshes takes a couple of minutes of one core.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import sys
import tempfile
from collections import Counter
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.scene.choice import choose_scene
from kitchen_tamp.kitchen.scene.kitchen_map import BoxSymbol
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.covering import DEFAULT_COVERING_TOLERANCE, SphereSet
from kitchen_tamp.motion.geometry.spheres.pair_tables import _stored_cells
from kitchen_tamp.motion.geometry.spheres.scene import _covered_shape
from kitchen_tamp.motion.geometry.spheres.stored_spheres import (
    ignoring_shipped,
    read_shipped,
    read_store,
    shipped_directory,
    sphere_cache_directory,
    write_shipped,
)
from kitchen_tamp.motion.geometry.spheres.tight_covering import TIGHT_COVERING_TOLERANCE
from kitchen_tamp.motion.geometry.urdf import read_urdf
from kitchen_tamp.planning import load_task
from kitchen_tamp.refinement.refine_action import PLANNING_MARGIN
from kitchen_tamp.world import describe_collision_checker

SHIPPED_KITCHENS = {"default": "problem.pddl", "galley": "problem.pddl"}
"""Kitchen folder -> a problem of it (to build the kitchen from)."""
TABLE_MARGINS = (0.0, PLANNING_MARGIN)
"""Margins the robot's pair tables are proved at: refinement's, and none (when a move's end is
closer than refinement's margin)."""

Store = tuple[dict[str, SphereSet], dict[str, npt.NDArray[np.int8]]]


def _gripper_widths(open_width: float, boxes: Iterable[BoxSymbol]) -> list[float]:
    """The openings the hand moves at: open, and holding each box across each of its sides that
    fits (a pair table of link 5 and a finger holds for one opening)."""
    sides = {float(size) for box in boxes for shape in read_urdf(str(box.urdf)).collisions
             if shape.kind == "box" for size in shape.size if size <= open_width}
    return [open_width, *sorted(sides)]


def _generate_in(cache: Path) -> Store:
    """Generates everything shipped with ``cache`` as the user cache; what it holds after."""
    os.environ["XDG_CACHE_HOME"] = str(cache)
    _covered_shape.cache_clear()
    _stored_cells.cache_clear()
    with ignoring_shipped():
        for folder, problem in SHIPPED_KITCHENS.items():
            choice = choose_scene(str(Path(__file__).parents[1] / "shipped_kitchens" / folder / problem))
            kitchen_map = choice.kitchen_map()
            task = load_task(choice.problem, choice.domain)
            with build_kitchen_for_task(task, kitchen_map=kitchen_map) as kitchen:
                for width in _gripper_widths(kitchen.robot.max_gripper_width, kitchen_map.boxes.values()):
                    kitchen.robot.set_gripper_width(width)
                    description = describe_collision_checker(kitchen.collision_checker())
                    for margin in TABLE_MARGINS:
                        SphereCollisionChecker(description, margin=margin)
            for box in kitchen_map.boxes.values():
                for index in range(len(read_urdf(str(box.urdf)).collisions)):
                    _covered_shape(str(box.urdf), index, DEFAULT_COVERING_TOLERANCE, False)
                    _covered_shape(str(box.urdf), index, TIGHT_COVERING_TOLERANCE, True)
    return read_store(sphere_cache_directory())


def generate() -> Store:
    """Every shipped sphere set and pair table, generated afresh."""
    saved = os.environ.get("XDG_CACHE_HOME")
    try:
        with tempfile.TemporaryDirectory(prefix="shipped-spheres-") as cache:
            return _generate_in(Path(cache))
    finally:
        if saved is None:
            os.environ.pop("XDG_CACHE_HOME", None)
        else:
            os.environ["XDG_CACHE_HOME"] = saved
        _covered_shape.cache_clear()
        _stored_cells.cache_clear()


# How far a regenerated sphere may lie from the shipped one (metres, centre or radius): the
# coverings' optimisation rounds differently on another CPU (seen: 1e-17 m on most shapes, 9 um on
# one), against coverings loose by millimetres; sphere counts and pair tables must agree exactly.
COVERING_AGREEMENT = 5e-5


def differences(generated: Store, shipped: Store) -> list[str]:
    """What differs between two stores, one line each (none when they agree): coverings by shape,
    within ``COVERING_AGREEMENT``; pair tables by their cells, since a table's key hashes the
    coverings' exact bits, which another CPU rounds otherwise."""
    flat = [{key: np.concatenate([s.centers.ravel(), s.radii]) for key, s in store[0].items()}
            for store in (generated, shipped)]
    new, old = flat
    lines = [f"covering {key}: not shipped" for key in sorted(set(new) - set(old))]
    lines += [f"covering {key}: shipped but not generated" for key in sorted(set(old) - set(new))]
    lines += [f"covering {key}: differs" for key in sorted(set(new) & set(old))
              if new[key].shape != old[key].shape
              or not np.allclose(new[key], old[key], rtol=0.0, atol=COVERING_AGREEMENT)]
    new_tables, old_tables = (_table_contents(store[1]) for store in (generated, shipped))
    lines += [f"pair table with cells {digest[:12]}: not shipped"
              for digest in sorted((new_tables - old_tables).elements())]
    lines += [f"pair table with cells {digest[:12]}: shipped but not generated"
              for digest in sorted((old_tables - new_tables).elements())]
    return lines


def _table_contents(tables: Mapping[str, npt.NDArray[Any]]) -> Counter[str]:
    return Counter(hashlib.sha256(f"{table.dtype}{table.shape}".encode() + table.tobytes()).hexdigest()
                   for table in tables.values())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--check", action="store_true", help="compare with what is shipped, write nothing")
    args = parser.parse_args(argv)
    generated = generate()
    if args.check:
        lines = differences(generated, read_shipped())
        print("\n".join(lines) or f"shipped sphere data up to date ({len(generated[0])} coverings, "
                                    f"{len(generated[1])} pair tables)")
        return 1 if lines else 0
    write_shipped(*generated, shipped_directory())
    print(f"wrote {len(generated[0])} coverings and {len(generated[1])} pair tables into "
          f"{shipped_directory()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
