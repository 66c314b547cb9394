"""What a kitchen's scene file says, as data: the counter, its surfaces (with regions on them),
drawers and fixed obstacles, the boxes, the robot on its mount; and the one error a bad scene
file gets (``SceneFileError``).

Frames: x points from the robot to the counter, y to the robot's left, z up; the
kitchen's base frame sits on the floor below the robot. All lengths in metres. The
schema, with the default kitchen as its example, is in the README ("Kitchens as data").
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Final

from kitchen_tamp.kitchen.errors import KitchenError

Vector = tuple[float, float, float]
Rgba = tuple[float, float, float, float]
Interval = tuple[float, float]

ROBOT_MODELS: Final = ("panda",)
RESERVED_NAMES: Final = frozenset(
    {"kitchen", "cabinet", "robot_mount", "panda", "slab", "burner", "handle", "mount"}
)
"""Body, link and material names the generated models use themselves."""
DRAWER_LINK_SUFFIXES: Final = ("_floor", "_handle", "_joint")


class SceneFileError(KitchenError):
    """A scene file that cannot describe a kitchen: one line with the file, the key and why."""

    def __init__(self, path: Path, key: str, detail: str) -> None:
        super().__init__(f"{path}: {key}: {detail}" if key else f"{path}: {detail}")
        self.path = path
        self.key = key


@dataclass(frozen=True)
class CounterSpec:
    """A cabinet standing on the floor with a slab on top, its front face towards the robot."""

    front: float
    depth: float
    width: float
    height: float
    slab: float
    panel: float
    colour: Rgba
    slab_colour: Rgba

    @property
    def x_range(self) -> Interval:
        return (self.front, self.front + self.depth)

    @property
    def y_range(self) -> Interval:
        return (-self.width / 2.0, self.width / 2.0)

    @property
    def slab_bottom(self) -> float:
        return self.height - self.slab


@dataclass(frozen=True)
class SurfaceSpec:
    """A ``surface``: a block whose top face (at ``height``) boxes stand on. On the counter
    it rests on the slab; beside the counter (an island, a side table) it stands on the floor."""

    name: str
    x_range: Interval
    y_range: Interval
    height: float
    colour: Rgba
    burners: bool


@dataclass(frozen=True)
class RegionSpec:
    """A ``region`` on a surface (a plate, a tray, a sink, a burner): a thin slab on the surface's
    face that objects stand on, named so a domain can say what is on it. ``kind`` is a word a
    domain's binding may give its own PDDL type (``sink``, ``burner``); default ``region``."""

    name: str
    surface: str
    x_range: Interval
    y_range: Interval
    thickness: float
    kind: str
    colour: Rgba


@dataclass(frozen=True)
class ObstacleSpec:
    """A fixed block (a wall, a shelf post) that is no symbol: it stands on the surface it lies
    in, else on the counter's slab or the floor, up to ``height``."""

    name: str
    x_range: Interval
    y_range: Interval
    height: float
    colour: Rgba


@dataclass(frozen=True)
class HandleSpec:
    """A bar in front of the drawer on two posts."""

    bar: Vector
    standoff: float
    """From the drawer front to the bar's centre."""
    post: float
    """Cross-section of each post."""


@dataclass(frozen=True)
class DrawerSpec:
    """An ``openable``: an open-top tray in its own cavity under the slab, pulled towards the robot."""

    name: str
    inner: Vector
    """Length along the pull, width, wall height above the floor."""
    y: float
    travel: float
    handle: HandleSpec
    wall: float
    gap: float
    """Between the tray and its cavity on every side."""
    colour: Rgba

    @property
    def outer(self) -> Vector:
        length, width, height = self.inner
        return (length + 2 * self.wall, width + 2 * self.wall, height + self.wall)

    @property
    def cavity_y(self) -> Interval:
        half = self.outer[1] / 2.0 + self.gap
        return (self.y - half, self.y + half)


@dataclass(frozen=True)
class StartSpec:
    """A box's start on its support (which the problem's ``:init`` names): the centre's (x, y)
    in the kitchen frame and a turn about z, in degrees."""

    xy: tuple[float, float]
    yaw_degrees: float


@dataclass(frozen=True)
class BoxSpec:
    """A ``box``: a rigid graspable box with its own URDF."""

    name: str
    size: Vector
    mass: float
    friction: float
    colour: Rgba
    start: StartSpec | None = None
    """Where the box starts, if the scene says (else the layout finds a place)."""


@dataclass(frozen=True)
class MountSpec:
    """The block the robot stands on, centred at the origin; the robot's base is on its top face."""

    size: tuple[float, float]
    height: float
    colour: Rgba


@dataclass(frozen=True)
class KitchenSpec:
    """Everything one scene file says."""

    path: Path
    name: str
    robot: str
    mount: MountSpec
    counter: CounterSpec
    surfaces: tuple[SurfaceSpec, ...]
    drawers: tuple[DrawerSpec, ...]
    boxes: tuple[BoxSpec, ...]
    regions: tuple[RegionSpec, ...] = ()
    obstacles: tuple[ObstacleSpec, ...] = ()

    def surface_named(self, name: str) -> SurfaceSpec | None:
        """The surface called ``name``, if any."""
        return next((s for s in self.surfaces if s.name == name), None)

    def on_counter(self, surface: SurfaceSpec | ObstacleSpec) -> bool:
        """Whether ``surface`` rests on the counter's slab (else it stands on the floor)."""
        counter = self.counter
        return overlap(surface.x_range, counter.x_range) and overlap(surface.y_range, counter.y_range)

    def obstacle_base(self, obstacle: ObstacleSpec) -> float:
        """The height an obstacle stands on: the face of the surface it lies in, else the
        counter's top if it is over the counter, else the floor."""
        for surface in self.surfaces:
            if contains(surface.x_range, obstacle.x_range) and contains(surface.y_range, obstacle.y_range):
                return surface.height
        return self.counter.height if self.on_counter(obstacle) else 0.0


def overlap(a: Interval, b: Interval) -> bool:
    """Whether two open intervals share a stretch."""
    return a[0] < b[1] and b[0] < a[1]


def contains(outer: Interval, inner: Interval) -> bool:
    """Whether ``inner`` lies within ``outer``."""
    return outer[0] <= inner[0] and inner[1] <= outer[1]
