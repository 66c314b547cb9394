"""Reading a kitchen's scene file (TOML, with ``tomllib``) into a ``KitchenSpec``; every mistake
is a ``SceneFileError`` naming the file, the key and what is wrong.

Frames: x points from the robot to the counter, y to the robot's left, z up; the
kitchen's base frame sits on the floor below the robot. All lengths in metres. The
schema, with an example, is in the README ("Kitchens as data").
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Final

from kitchen_tamp.kitchen.scene.checks import check_layout
from kitchen_tamp.kitchen.scene.region_checks import check_regions_and_obstacles
from kitchen_tamp.kitchen.scene.spec import (
    ROBOT_MODELS,
    BoxSpec,
    CounterSpec,
    DrawerSpec,
    HandleSpec,
    Interval,
    KitchenSpec,
    MountSpec,
    ObstacleSpec,
    RegionSpec,
    Rgba,
    SceneFileError,
    StartSpec,
    SurfaceSpec,
    Vector,
)

__all__ = ["SceneFileError", "parse_scene", "read_scene"]

NAME_PATTERN: Final = re.compile(r"[A-Za-z][A-Za-z0-9_\-]*")
SCHEMA_KEYS: Final = {
    "": ("name", "robot", "counter", "surfaces", "drawers", "boxes", "regions", "obstacles"),
    "robot": ("model", "mount"),
    "mount": ("size", "height", "colour"),
    "counter": ("front", "depth", "width", "height", "slab", "panel", "colour", "slab_colour"),
    "surfaces": ("name", "extent", "height", "colour", "burners"),
    "drawers": ("name", "handle", "size", "y", "travel", "wall", "gap", "colour"),
    "handle": ("bar", "standoff", "post"),
    "boxes": ("name", "size", "mass", "friction", "colour", "at", "yaw"),
    "regions": ("name", "surface", "extent", "kind", "thickness", "colour"),
    "obstacles": ("name", "extent", "height", "colour"),
}
"""The keys each kind of table may hold: a missing key's hint proposes only a present key that is
none of them (a misspelling), never another key of the schema."""


class _Table:
    """One TOML table with the key path that leads to it, for error messages."""

    def __init__(self, path: Path, where: str, data: object, kind: str = "") -> None:
        if not isinstance(data, dict):
            raise SceneFileError(path, where, f"expected a table, got {type(data).__name__}")
        self.path = path
        self.kind = kind
        self.where = where
        self.data: dict[str, Any] = data
        self.used: set[str] = set()

    def key(self, name: str) -> str:
        return f"{self.where}.{name}" if self.where else name

    def error(self, name: str, detail: str) -> SceneFileError:
        return SceneFileError(self.path, self.key(name), detail)

    def raw(self, name: str, default: object = None) -> object:
        self.used.add(name)
        if name not in self.data:
            if default is None:
                known = set(SCHEMA_KEYS.get(self.kind, ())) | self.used
                close = difflib.get_close_matches(name, [k for k in self.data if k not in known], 1)
                hint = f" (is {close[0]!r} a misspelling?)" if close else ""
                raise SceneFileError(self.path, self.where or name, f"missing key {name!r}{hint}")
            return default
        return self.data[name]

    def table(self, name: str) -> _Table:
        return _Table(self.path, self.key(name), self.raw(name), name)

    def text(self, name: str, default: str | None = None) -> str:
        value = self.raw(name, default)
        if not isinstance(value, str) or not value:
            raise self.error(name, f"expected a non-empty string, got {value!r}")
        return value

    def number(self, name: str, default: float | None = None, positive: bool = True) -> float:
        return self._checked(name, self.raw(name, default), positive)

    def _checked(self, name: str, value: object, positive: bool) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
            raise self.error(name, f"expected a number, got {value!r}")
        if positive and value <= 0.0:
            raise self.error(name, f"must be positive, got {value!r}")
        return float(value)

    def numbers(self, name: str, count: int, positive: bool = True, default: object = None) -> list[float]:
        value = self.raw(name, default)
        if not isinstance(value, list) or len(value) != count:
            raise self.error(name, f"expected a list of {count} numbers, got {value!r}")
        return [self._checked(name, v, positive) for v in value]

    def vector(self, name: str, default: object = None) -> Vector:
        x, y, z = self.numbers(name, 3, default=default)
        return (x, y, z)

    def interval(self, value: object, name: str) -> Interval:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(name, f"expected [low, high], got {value!r}")
        low, high = (self._checked(name, v, positive=False) for v in value)
        if high <= low:
            raise self.error(name, f"[low, high] must have high > low, got {value!r}")
        return (low, high)

    def colour(self, name: str, default: Rgba | None = None) -> Rgba:
        values = self.numbers(name, 4, positive=False, default=list(default) if default else None)
        if any(not 0.0 <= v <= 1.0 for v in values):
            raise self.error(name, f"RGBA values must lie in [0, 1], got {values}")
        return (values[0], values[1], values[2], values[3])

    def flag(self, name: str, default: bool) -> bool:
        value = self.raw(name, default) if name in self.data else default
        self.used.add(name)
        if not isinstance(value, bool):
            raise self.error(name, f"expected true or false, got {value!r}")
        return value

    def tables(self, name: str) -> list[_Table]:
        value = self.raw(name, []) if name in self.data else []
        self.used.add(name)
        if not isinstance(value, list):
            raise self.error(name, "expected an array of tables ([[" + name + "]])")
        return [_Table(self.path, f"{self.key(name)}[{i}]", item, name) for i, item in enumerate(value)]

    def named(self) -> str:
        """Read this table's ``name`` and use it in later key paths."""
        name = self.text("name")
        if not NAME_PATTERN.fullmatch(name):
            raise self.error("name", f"{name!r} is not a PDDL name (a letter, then letters, digits, _ or -)")
        self.where = self.where.rsplit("[", 1)[0] + f".{name}"
        return name

    def finish(self) -> None:
        unknown = sorted(set(self.data) - self.used)
        if unknown:
            raise SceneFileError(self.path, self.key(unknown[0]), "unknown key")


GREY: Final = (0.55, 0.55, 0.58, 1.0)


def read_scene(path: Path) -> KitchenSpec:
    """Read and check a scene file; raises ``SceneFileError`` naming the file and the key."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise SceneFileError(path, "", f"cannot read scene file: {error}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise SceneFileError(path, "", f"not valid TOML: {error}") from None
    return parse_scene(path, data)


def parse_scene(path: Path, data: Mapping[str, object]) -> KitchenSpec:
    """The kitchen a scene file's parsed TOML describes (see ``read_scene``)."""
    root = _Table(path, "", dict(data))
    name = root.text("name")
    robot_table = root.table("robot")
    robot = robot_table.text("model")
    if robot not in ROBOT_MODELS:
        raise robot_table.error("model", f"unknown robot {robot!r}, known: {', '.join(ROBOT_MODELS)}")
    mount_table = robot_table.table("mount")
    mount_xy = mount_table.numbers("size", 2)
    mount = MountSpec(
        (mount_xy[0], mount_xy[1]), mount_table.number("height"), mount_table.colour("colour", GREY)
    )
    mount_table.finish()
    robot_table.finish()
    counter = _counter(root.table("counter"))
    surfaces = tuple(_surface(t) for t in root.tables("surfaces"))
    drawers = tuple(_drawer(t) for t in root.tables("drawers"))
    boxes = tuple(_box(t) for t in root.tables("boxes"))
    regions = tuple(_region(t) for t in root.tables("regions"))
    obstacles = tuple(_obstacle(t) for t in root.tables("obstacles"))
    root.finish()
    spec = KitchenSpec(path, name, robot, mount, counter, surfaces, drawers, boxes, regions, obstacles)
    check_layout(spec)
    check_regions_and_obstacles(spec)
    return spec


def _counter(table: _Table) -> CounterSpec:
    counter = CounterSpec(
        front=table.number("front"),
        depth=table.number("depth"),
        width=table.number("width"),
        height=table.number("height"),
        slab=table.number("slab"),
        panel=table.number("panel", 0.02),
        colour=table.colour("colour"),
        slab_colour=table.colour("slab_colour"),
    )
    table.finish()
    if counter.slab >= counter.height:
        raise table.error("slab", f"the slab ({counter.slab} m) is thicker than the counter is high")
    return counter


def _extent(table: _Table) -> tuple[Interval, Interval]:
    extent = table.raw("extent")
    if not isinstance(extent, list) or len(extent) != 2:
        raise table.error("extent", f"expected [[x_low, x_high], [y_low, y_high]], got {extent!r}")
    return table.interval(extent[0], "extent"), table.interval(extent[1], "extent")


def _surface(table: _Table) -> SurfaceSpec:
    name = table.named()
    x_range, y_range = _extent(table)
    surface = SurfaceSpec(
        name, x_range, y_range, table.number("height"), table.colour("colour"), table.flag("burners", False)
    )
    table.finish()
    return surface


REGION_THICKNESS: Final = 0.01
"""Default thickness (m) of a region's slab on its surface."""


def _region(table: _Table) -> RegionSpec:
    name = table.named()
    surface = table.text("surface")
    x_range, y_range = _extent(table)
    kind = table.text("kind", "region")
    if not NAME_PATTERN.fullmatch(kind):
        raise table.error("kind", f"{kind!r} is not a PDDL name (a letter, then letters, digits, _ or -)")
    region = RegionSpec(
        name, surface, x_range, y_range, table.number("thickness", REGION_THICKNESS), kind,
        table.colour("colour"),
    )
    table.finish()
    return region


def _obstacle(table: _Table) -> ObstacleSpec:
    name = table.named()
    x_range, y_range = _extent(table)
    obstacle = ObstacleSpec(name, x_range, y_range, table.number("height"), table.colour("colour", GREY))
    table.finish()
    return obstacle


def _start(table: _Table) -> StartSpec | None:
    if "at" not in table.data:
        if "yaw" in table.data:
            raise table.error("yaw", "a turn needs a start position: give 'at' = [x, y] too")
        return None
    x, y = table.numbers("at", 2, positive=False)
    return StartSpec((x, y), table.number("yaw", 0.0, positive=False))


def _drawer(table: _Table) -> DrawerSpec:
    name = table.named()
    handle_table = table.table("handle")
    handle = HandleSpec(
        handle_table.vector("bar"), handle_table.number("standoff"), handle_table.number("post", 0.015)
    )
    handle_table.finish()
    if handle.standoff <= handle.bar[0] / 2.0:
        raise handle_table.error("standoff", "must exceed half the bar's depth, or the bar hits the drawer")
    drawer = DrawerSpec(
        name,
        table.vector("size"),
        table.number("y", positive=False),
        table.number("travel"),
        handle,
        table.number("wall", 0.015),
        table.number("gap", 0.01),
        table.colour("colour"),
    )
    table.finish()
    if drawer.travel >= drawer.outer[0]:
        raise table.error("travel", f"{drawer.travel} m pulls the tray out of its cavity")
    return drawer


def _box(table: _Table) -> BoxSpec:
    name = table.named()
    box = BoxSpec(
        name,
        table.vector("size"),
        table.number("mass"),
        table.number("friction"),
        table.colour("colour"),
        _start(table),
    )
    table.finish()
    return box


