"""Where each box starts: its support from the problem's ``:init`` (through the domain's
binding), then its pose on that support -- the scene file's start if it gives one, else a
deterministic layout in rows, and a box on a box centred on its top face.

A box in an open drawer is laid out on the part of the drawer's floor that is out from under the
counter's slab (from there it can be lifted out); a box that does not fit there is refused by
name.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.binding import RELATIONS, DomainBinding
from kitchen_tamp.kitchen.errors import UnsupportedInitialStateError
from kitchen_tamp.kitchen.scene.kitchen_map import KitchenMap
from kitchen_tamp.kitchen.scene.regions import SupportRegion
from kitchen_tamp.kitchen.scene.spec import StartSpec
from kitchen_tamp.planning import Atom, atom_text
from kitchen_tamp.world import FloatArray, Pose, rotation_about_axis

SUPPORT_RELATIONS: Final = ("on_surface", "on_region", "on_box", "in_drawer")
SLAB_CLEARANCE: Final = 0.02
"""A box laid out in an open drawer keeps this far (m) in front of the slab's front edge."""

Size = tuple[float, float, float]


def start_supports(
    init_atoms: Iterable[Atom], boxes: Iterable[str], kitchen_map: KitchenMap
) -> dict[str, str]:
    """Box -> the surface, region, drawer or box ``:init`` puts it on or in, exactly one each,
    ordered so that a box comes after the box it stands on."""
    binding = kitchen_map.binding
    held = set(binding.predicates_for("holding"))
    resting = _support_predicates(binding)
    supports: dict[str, list[str]] = {box: [] for box in boxes}
    for atom in sorted(init_atoms):
        if atom[0] in held:
            raise UnsupportedInitialStateError(
                f"{atom_text(atom)} in :init: the kitchen starts with an empty hand; "
                "put the box on a surface or in the drawer instead"
            )
        if atom[0] in resting and len(atom) == 3 and atom[1] in supports:
            kinds = resting[atom[0]]
            if kitchen_map.type_of(atom[2]) in kinds:
                supports[atom[1]].append(atom[2])
    for box, places in supports.items():
        if len(places) != 1:
            where = "nowhere" if not places else " and ".join(places)
            raise UnsupportedInitialStateError(
                f"box {box!r} must start on exactly one surface or in one drawer, :init puts it {where}"
            )
    return _bases_first({box: places[0] for box, places in supports.items()})


def _support_predicates(binding: DomainBinding) -> dict[str, set[str]]:
    """Predicate -> the kinds of support its relations put a box on."""
    kinds: dict[str, set[str]] = {}
    for relation in SUPPORT_RELATIONS:
        for predicate in binding.predicates_for(relation):
            kinds.setdefault(predicate, set()).add(RELATIONS[relation][1])
    return kinds


def _bases_first(supports: Mapping[str, str]) -> dict[str, str]:
    ordered: dict[str, str] = {}
    pending = dict(sorted(supports.items()))
    while pending:
        ready = [box for box, support in pending.items() if support not in pending]
        if not ready:
            raise UnsupportedInitialStateError(
                f"the boxes {', '.join(pending)} stand on each other in a circle"
            )
        for box in ready:
            ordered[box] = pending.pop(box)
    return ordered


def upright(
    region: SupportRegion, xy_local: Sequence[float] | FloatArray, size: Size, yaw: float, gap: float
) -> Pose:
    """A box standing on its bottom face at ``xy_local`` in the region's frame, turned by ``yaw``."""
    local = np.array([xy_local[0], xy_local[1], size[2] / 2.0 + gap])
    rotation = rotation_about_axis([0.0, 0.0, 1.0], yaw)
    return region.world_from_region @ Pose.from_rotation(local, rotation)


def _row(
    region: SupportRegion, sizes: Sequence[Size], along: int, across: float, gap: float
) -> list[Pose] | None:
    """Boxes side by side along the region's axis ``along``, centred, at ``across`` on the other."""
    hx, hy = region.half_size
    length = 2.0 * (hx if along == 0 else hy)
    footprint = [s[along] for s in sizes]
    spacing = (length - sum(footprint)) / (len(sizes) + 1)
    if spacing <= 0.0:
        return None
    poses = []
    cursor = -length / 2.0
    for size, width in zip(sizes, footprint, strict=True):
        cursor += spacing + width / 2.0
        xy = [0.0, 0.0]
        xy[along], xy[1 - along] = cursor, across
        poses.append(upright(region, xy, size, 0.0, gap))
        cursor += width / 2.0
    return poses


def row_poses(region: SupportRegion, names: Sequence[str], sizes: Sequence[Size], gap: float) -> list[Pose]:
    """Upright box poses side by side along the region's longer side, centred; in two or more
    rows (across the shorter side) when one row is too long."""
    if not sizes:
        return []
    hx, hy = region.half_size
    along = 0 if hx >= hy else 1
    width = 2.0 * (hy if along == 0 else hx)
    for rows in range(1, len(sizes) + 1):
        members = [list(range(r, len(sizes), rows)) for r in range(rows)]
        depths = [max(sizes[i][1 - along] for i in row) for row in members]
        spacing = (width - sum(depths)) / (rows + 1)
        if spacing < 0.0 or (rows == 1 and depths[0] > width):
            break
        poses: dict[int, Pose] = {}
        cursor = -width / 2.0
        for row, depth in zip(members, depths, strict=True):
            cursor += (spacing if rows > 1 else (width - depth) / 2.0) + depth / 2.0
            placed = _row(region, [sizes[i] for i in row], along, cursor if rows > 1 else 0.0, gap)
            if placed is None:
                break
            poses.update(zip(row, placed, strict=True))
            cursor += depth / 2.0
        if len(poses) == len(sizes):
            return [poses[i] for i in range(len(sizes))]
    raise UnsupportedInitialStateError(
        f"the boxes {', '.join(names)} do not fit side by side in {region.name!r}"
    )


def explicit_pose(region: SupportRegion, box: str, start: StartSpec, size: Size, gap: float) -> Pose:
    """The scene file's start of a box on the support ``:init`` names, checked to be over it."""
    point = np.array([start.xy[0], start.xy[1], region.top_z])
    if not region.contains_xy(point):
        raise UnsupportedInitialStateError(
            f"box {box!r} starts at ({start.xy[0]}, {start.xy[1]}) in the scene file, which is not "
            f"over {region.name!r}, where :init puts it"
        )
    local = region.local_point(point)
    yaw = np.radians(start.yaw_degrees) - float(np.arctan2(region.world_from_region.rotation[1, 0],
                                                           region.world_from_region.rotation[0, 0]))
    return upright(region, local[:2], size, float(yaw), gap)


def exposed_floor(region: SupportRegion, front_x: float, boxes: Sequence[str]) -> SupportRegion:
    """The part of an open drawer's floor in front of ``front_x`` (the slab's front edge, less
    ``SLAB_CLEARANCE``), where a box can be lifted straight out; refused naming the boxes when
    no part of it is."""
    rotation = region.world_from_region.rotation
    if abs(abs(rotation[0, 0]) - 1.0) > 1e-6:
        return region  # a drawer that does not slide along x: its whole floor
    hx, hy = region.half_size
    boundary = float(region.local_point(np.array([front_x - SLAB_CLEARANCE, 0.0, 0.0]))[0])
    low, high = (-hx, min(hx, boundary)) if rotation[0, 0] > 0 else (max(-hx, boundary), hx)
    if high - low <= 0.0:
        raise UnsupportedInitialStateError(
            f"{', '.join(boxes)} cannot start in the open drawer {region.name!r}: all of its floor is "
            "under the counter's slab"
        )
    centre = region.world_from_region @ Pose(((low + high) / 2.0, 0.0, 0.0))
    return SupportRegion(region.name, centre, ((high - low) / 2.0, hy), region.ceiling_z)
