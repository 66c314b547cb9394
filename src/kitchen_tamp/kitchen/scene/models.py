"""The URDF files of a kitchen, written from its scene file: the kitchen (cabinet with one cavity
per drawer, slab, surfaces with their regions, obstacles, drawers with handles, robot mount) and
one file per box.

``model_texts`` gives the texts; ``model_files`` writes them once into a cache folder
named by their content (never into the working folder), so PyBullet and Drake load
real files and a changed scene gets new files.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Final

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.kitchen.scene.spec import (
    DrawerSpec,
    KitchenSpec,
    ObstacleSpec,
    RegionSpec,
    Rgba,
    SurfaceSpec,
    Vector,
)
from kitchen_tamp.user_cache import cache_directory

KITCHEN_FILE: Final = "kitchen.urdf"
CABINET_LINK: Final = "cabinet"
MOUNT_LINK: Final = "robot_mount"
DRAWER_MASS: Final = 2.0
BURNER_COLOUR: Final = (0.75, 0.15, 0.10, 1.0)
HANDLE_COLOUR: Final = (0.75, 0.75, 0.78, 1.0)


def joint_name(drawer: str) -> str:
    return f"{drawer}_joint"


def floor_link(drawer: str) -> str:
    return f"{drawer}_floor"


def handle_link(drawer: str) -> str:
    return f"{drawer}_handle"


@dataclass(frozen=True)
class BoxPart:
    """One box primitive of a link, placed at ``center`` in the link frame."""

    center: Vector
    size: Vector
    material: str


@dataclass(frozen=True)
class CylinderPart:
    """A visual-only cylinder (burner rings), axis along z."""

    center: Vector
    radius: float
    length: float
    material: str


Part = BoxPart | CylinderPart


def _fmt(values: tuple[float, ...]) -> str:
    return " ".join(f"{v:.6g}" for v in values)


def _box_xml(part: BoxPart) -> str:
    origin = f'<origin xyz="{_fmt(part.center)}" rpy="0 0 0"/>'
    geometry = f'<geometry><box size="{_fmt(part.size)}"/></geometry>'
    visual = f'    <visual>{origin}{geometry}<material name="{part.material}"/></visual>\n'
    return visual + f"    <collision>{origin}{geometry}</collision>\n"


def _cylinder_xml(part: CylinderPart) -> str:
    origin = f'<origin xyz="{_fmt(part.center)}" rpy="0 0 0"/>'
    geometry = f'<geometry><cylinder radius="{part.radius:.6g}" length="{part.length:.6g}"/></geometry>'
    return f'    <visual>{origin}{geometry}<material name="{part.material}"/></visual>\n'


def _inertia_xml(mass: float, size: Vector) -> str:
    sx, sy, sz = size
    ixx = mass * (sy**2 + sz**2) / 12.0
    iyy = mass * (sx**2 + sz**2) / 12.0
    izz = mass * (sx**2 + sy**2) / 12.0
    return (
        '    <inertial><origin xyz="0 0 0" rpy="0 0 0"/>'
        f'<mass value="{mass:.6g}"/>'
        f'<inertia ixx="{ixx:.6g}" ixy="0" ixz="0" iyy="{iyy:.6g}" iyz="0" izz="{izz:.6g}"/>'
        "</inertial>\n"
    )


def _link_xml(name: str, parts: Sequence[Part], mass: float = 0.0) -> str:
    body = _inertia_xml(mass, (0.1, 0.1, 0.1))
    for part in parts:
        body += _box_xml(part) if isinstance(part, BoxPart) else _cylinder_xml(part)
    return f'  <link name="{name}">\n{body}  </link>\n'


def _fixed_joint_xml(parent: str, child: str) -> str:
    return (
        f'  <joint name="{parent}_to_{child}" type="fixed">'
        f'<parent link="{parent}"/><child link="{child}"/>'
        '<origin xyz="0 0 0" rpy="0 0 0"/></joint>\n'
    )


def _material_xml(name: str, rgba: Rgba) -> str:
    return f'  <material name="{name}"><color rgba="{_fmt(rgba)}"/></material>\n'


def _box_between(lo: Vector, hi: Vector, material: str) -> BoxPart:
    center = tuple((a + b) / 2.0 for a, b in zip(lo, hi, strict=True))
    size = tuple(b - a for a, b in zip(lo, hi, strict=True))
    if not all(s > 0.0 for s in size):
        raise ValueError(f"empty box between {lo} and {hi}")
    return BoxPart((center[0], center[1], center[2]), (size[0], size[1], size[2]), material)


def _cavity_z(spec: KitchenSpec, drawer: DrawerSpec) -> tuple[float, float]:
    """Bottom and top of a drawer's cavity: it hangs right under the slab."""
    top = spec.counter.slab_bottom
    return (top - drawer.outer[2] - 2 * drawer.gap, top)


def cabinet_parts(spec: KitchenSpec) -> list[Part]:
    """The slab, then the cabinet below it cut into boxes around one cavity per drawer:
    the full-height strips between cavities (left to right), then below and behind each cavity."""
    counter = spec.counter
    x0, x1 = counter.x_range
    y0, y1 = counter.y_range
    slab_bottom = counter.slab_bottom
    parts: list[Part] = [_box_between((x0, y0, slab_bottom), (x1, y1, counter.height), "slab")]
    drawers = sorted(spec.drawers, key=lambda d: d.y)
    edges = [y0, *(y for d in drawers for y in d.cavity_y), y1]
    for low, high in zip(edges[::2], edges[1::2], strict=True):
        if high > low:
            parts.append(_box_between((x0, low, 0.0), (x1, high, slab_bottom), "cabinet"))
    for drawer in drawers:
        low, high = drawer.cavity_y
        bottom, top = _cavity_z(spec, drawer)
        back = x0 + drawer.outer[0] + drawer.gap
        parts.append(_box_between((x0, low, 0.0), (x1, high, bottom), "cabinet"))
        parts.append(_box_between((back, low, bottom), (x1, high, top), "cabinet"))
    return parts


def surface_parts(spec: KitchenSpec, surface: SurfaceSpec) -> list[Part]:
    """A block from what it stands on (the slab, or the floor beside the counter) up to its
    face; a stove gets two burner rings on top (visual only)."""
    counter = spec.counter
    base = counter.height if spec.on_counter(surface) else 0.0
    (sx0, sx1), (sy0, sy1) = surface.x_range, surface.y_range
    top = surface.height
    parts: list[Part] = [_box_between((sx0, sy0, base), (sx1, sy1, top), surface.name)]
    if surface.burners:
        burner_x = (sx0 + 0.3 * (sx1 - sx0), sx0 + 0.7 * (sx1 - sx0))
        burner_y = (sy0 + 0.3 * (sy1 - sy0), sy0 + 0.7 * (sy1 - sy0))
        for bx, by in zip(burner_x, burner_y, strict=True):
            parts.append(CylinderPart((bx, by, top + 0.0005), 0.05, 0.001, "burner"))
            parts.append(CylinderPart((bx, by, top + 0.001), 0.035, 0.001, surface.name))
    return parts


def region_parts(spec: KitchenSpec, region: RegionSpec) -> list[Part]:
    """A slab ``thickness`` thick on its surface's face."""
    surface = spec.surface_named(region.surface)
    assert surface is not None  # the scene's checks found it
    (x0, x1), (y0, y1) = region.x_range, region.y_range
    return [_box_between((x0, y0, surface.height), (x1, y1, surface.height + region.thickness), region.name)]


def obstacle_parts(spec: KitchenSpec, obstacle: ObstacleSpec) -> list[Part]:
    """A block from what it stands on up to its height."""
    (x0, x1), (y0, y1) = obstacle.x_range, obstacle.y_range
    return [_box_between((x0, y0, spec.obstacle_base(obstacle)), (x1, y1, obstacle.height), obstacle.name)]


def drawer_xml(spec: KitchenSpec, drawer: DrawerSpec) -> str:
    """The tray (walls), its prismatic joint, its floor and its handle. The tray's frame is the
    outer front face's centre at the floor of the tray; the joint pulls it towards the robot."""
    d_len, d_wid, d_hgt = drawer.outer
    in_len, in_wid, _ = drawer.inner
    w = drawer.wall
    name = drawer.name
    walls: list[Part] = [
        _box_between((0.0, -d_wid / 2, 0.0), (w, d_wid / 2, d_hgt), name),  # front
        _box_between((d_len - w, -d_wid / 2, 0.0), (d_len, d_wid / 2, d_hgt), name),  # back
        _box_between((w, -d_wid / 2, 0.0), (d_len - w, -in_wid / 2, d_hgt), name),  # right
        _box_between((w, in_wid / 2, 0.0), (d_len - w, d_wid / 2, d_hgt), name),  # left
    ]
    floor: list[Part] = [_box_between((w, -in_wid / 2, 0.0), (w + in_len, in_wid / 2, w), name)]
    handle = drawer.handle
    bar_x, bar_z = -handle.standoff, d_hgt / 2
    bx, by, bz = handle.bar
    px, pyz = handle.standoff - bx / 2, handle.post
    low, high = (bar_x - bx / 2, -by / 2, bar_z - bz / 2), (bar_x + bx / 2, by / 2, bar_z + bz / 2)
    parts: list[Part] = [_box_between(low, high, "handle")]
    for post_y in (-(by / 2 - pyz), by / 2 - pyz):
        low, high = (-px, post_y - pyz / 2, bar_z - pyz / 2), (0.0, post_y + pyz / 2, bar_z + pyz / 2)
        parts.append(_box_between(low, high, "handle"))
    origin = (spec.counter.front, drawer.y, _cavity_z(spec, drawer)[0] + drawer.gap)
    joint = (
        f'  <joint name="{joint_name(name)}" type="prismatic">'
        f'<parent link="{CABINET_LINK}"/><child link="{name}"/>'
        f'<origin xyz="{_fmt(origin)}" rpy="0 0 0"/>'
        '<axis xyz="-1 0 0"/>'
        f'<limit lower="0" upper="{drawer.travel:.6g}" effort="100" velocity="0.5"/>'
        "</joint>\n"
    )
    return (
        _link_xml(name, walls, mass=DRAWER_MASS)
        + joint
        + _link_xml(floor_link(name), floor)
        + _fixed_joint_xml(name, floor_link(name))
        + _link_xml(handle_link(name), parts)
        + _fixed_joint_xml(name, handle_link(name))
    )


def _header(spec: KitchenSpec, robot_name: str) -> str:
    return (
        '<?xml version="1.0"?>\n'
        f"<!-- Generated from the {spec.name} kitchen's scene file by kitchen_tamp.kitchen.scene.models; "
        "edit the scene, not this file. -->\n"
        f'<robot name="{robot_name}">\n'
    )


def kitchen_urdf(spec: KitchenSpec) -> str:
    """The kitchen: cabinet with slab and drawer cavities, surfaces, drawers, robot mount."""
    materials = [("cabinet", spec.counter.colour), ("slab", spec.counter.slab_colour)]
    for surface in spec.surfaces:
        materials.append((surface.name, surface.colour))
        if surface.burners and all(m != "burner" for m, _ in materials):
            materials.append(("burner", BURNER_COLOUR))
    materials += [(d.name, d.colour) for d in spec.drawers]
    materials += [(r.name, r.colour) for r in spec.regions] + [(o.name, o.colour) for o in spec.obstacles]
    materials += [("handle", HANDLE_COLOUR), ("mount", spec.mount.colour)]
    mx, my = spec.mount.size
    mount = [_box_between((-mx / 2, -my / 2, 0.0), (mx / 2, my / 2, spec.mount.height), "mount")]
    text = _header(spec, "kitchen") + "".join(_material_xml(n, c) for n, c in materials)
    text += _link_xml(CABINET_LINK, cabinet_parts(spec))
    text += _link_xml(MOUNT_LINK, mount) + _fixed_joint_xml(CABINET_LINK, MOUNT_LINK)
    for surface in spec.surfaces:
        text += _link_xml(surface.name, surface_parts(spec, surface))
        text += _fixed_joint_xml(CABINET_LINK, surface.name)
    for region in spec.regions:
        text += _link_xml(region.name, region_parts(spec, region))
        text += _fixed_joint_xml(CABINET_LINK, region.name)
    for obstacle in spec.obstacles:
        text += _link_xml(obstacle.name, obstacle_parts(spec, obstacle))
        text += _fixed_joint_xml(CABINET_LINK, obstacle.name)
    text += "".join(drawer_xml(spec, drawer) for drawer in spec.drawers)
    return text + "</robot>\n"


def box_urdf(spec: KitchenSpec, name: str) -> str:
    """A graspable box with its own colour, mass, friction and inertia."""
    box = next(b for b in spec.boxes if b.name == name)
    part = BoxPart((0.0, 0.0, 0.0), box.size, name)
    contact = f'    <contact><lateral_friction value="{box.friction:.6g}"/></contact>\n'
    return (
        _header(spec, name)
        + _material_xml(name, box.colour)
        + f'  <link name="{name}">\n'
        + contact
        + _inertia_xml(box.mass, box.size)
        + _box_xml(part)
        + "  </link>\n</robot>\n"
    )


def model_texts(spec: KitchenSpec) -> dict[str, str]:
    """File name -> URDF text for the kitchen and every box."""
    texts = {KITCHEN_FILE: kitchen_urdf(spec)}
    texts.update({f"{box.name}.urdf": box_urdf(spec, box.name) for box in spec.boxes})
    return texts


@dataclass(frozen=True)
class ModelFiles:
    """Where a kitchen's generated URDFs are on disk."""

    kitchen: Path
    boxes: MappingProxyType[str, Path]


def write_models(spec: KitchenSpec, folder: Path) -> dict[str, Path]:
    """Write the kitchen's URDFs into ``folder`` (atomically, skipping files already equal)."""
    paths = {}
    for file_name, text in model_texts(spec).items():
        path = folder / file_name
        if not (path.exists() and path.read_text(encoding="utf-8") == text):
            write_atomically(path, text)
        paths[file_name] = path
    return paths


def model_files(spec: KitchenSpec) -> ModelFiles:
    """The kitchen's URDFs, written once into a folder named by their content in the user's
    cache (the one the PDDL parsers use), or the system's temporary folder if that cannot be
    written."""
    texts = model_texts(spec)
    digest = hashlib.sha256("\0".join(f"{k}\0{v}" for k, v in sorted(texts.items())).encode()).hexdigest()
    folder_name = f"models-{digest[:20]}"
    try:
        paths = write_models(spec, cache_directory() / folder_name)
    except (OSError, RuntimeError):  # RuntimeError: no home directory to find the cache in
        paths = write_models(spec, Path(tempfile.gettempdir()) / f"kitchen_tamp-{os.getuid()}" / folder_name)
    return ModelFiles(
        paths[KITCHEN_FILE], MappingProxyType({b.name: paths[f"{b.name}.urdf"] for b in spec.boxes})
    )
