"""The geometry of the toy rooms domain: rectangular rooms, doorways between them, disc obstacles.

Rooms tile the plane without overlapping; a doorway is a gap in the wall two
rooms share. The robot is a disc of radius ``robot_radius`` that moves in
straight lines. Walls never need checking: a robot whose centre stays at least
its radius inside a room cannot touch that room's walls, and it crosses a wall
only through a doorway, perpendicular to it. Obstacles are discs: a *pillar*
stands inside a room, a *crate* sits in a doorway and blocks it. The
abstraction does not see obstacles, so a blocked doorway is only found out by
sampling.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

Point = npt.NDArray[np.float64]
"""A position ``[x, y]``."""


def point(x: float, y: float) -> Point:
    return np.array([x, y], dtype=np.float64)


@dataclass(frozen=True)
class Room:
    """An axis-aligned rectangle."""

    name: str
    x_min: float
    y_min: float
    x_max: float
    y_max: float

    @property
    def center(self) -> Point:
        return point((self.x_min + self.x_max) / 2, (self.y_min + self.y_max) / 2)

    def contains(self, position: Point, margin: float = 0.0) -> bool:
        """Whether ``position`` lies inside, at least ``margin`` from every wall."""
        x, y = float(position[0]), float(position[1])
        return (self.x_min + margin <= x <= self.x_max - margin
                and self.y_min + margin <= y <= self.y_max - margin)

    def sample_point(self, rng: np.random.Generator, margin: float) -> Point:
        """A point uniformly inside the room, at least ``margin`` from every wall."""
        return point(float(rng.uniform(self.x_min + margin, self.x_max - margin)),
                     float(rng.uniform(self.y_min + margin, self.y_max - margin)))


@dataclass(frozen=True)
class Door:
    """A doorway of ``width`` centred on ``center``, in the wall between ``rooms``.

    ``normal`` is the unit vector across the wall, pointing from ``rooms[0]`` into ``rooms[1]``.
    """

    name: str
    rooms: tuple[str, str]
    center: tuple[float, float]
    normal: tuple[float, float]
    width: float

    def other_room(self, room: str) -> str:
        if room not in self.rooms:
            raise ValueError(f"door {self.name} does not open into room {room}")
        return self.rooms[1] if room == self.rooms[0] else self.rooms[0]

    def point_inside(self, room: str, depth: float) -> Point:
        """The point ``depth`` in front of the doorway's centre on ``room``'s side."""
        if room not in self.rooms:
            raise ValueError(f"door {self.name} does not open into room {room}")
        sign = 1.0 if room == self.rooms[1] else -1.0
        return point(self.center[0] + sign * depth * self.normal[0],
                     self.center[1] + sign * depth * self.normal[1])


@dataclass(frozen=True)
class DiscObstacle:
    """A round obstacle: ``kind`` is ``"pillar"`` (in a room) or ``"crate"`` (in a doorway)."""

    name: str
    center: tuple[float, float]
    radius: float
    kind: str = "pillar"


def distance_to_segment(center: Point, start: Point, end: Point) -> float:
    """The distance from ``center`` to the segment ``start``-``end``."""
    direction = end - start
    length_squared = float(direction @ direction)
    if length_squared == 0.0:
        return float(np.linalg.norm(center - start))
    t = min(1.0, max(0.0, float((center - start) @ direction) / length_squared))
    return float(np.linalg.norm(center - (start + t * direction)))


@dataclass(frozen=True)
class RoomsWorld:
    """Rooms, the doors between them and the obstacles, for a disc robot of ``robot_radius``."""

    rooms: tuple[Room, ...]
    doors: tuple[Door, ...]
    obstacles: tuple[DiscObstacle, ...] = ()
    robot_radius: float = 0.06
    _rooms_by_name: dict[str, Room] = field(init=False, repr=False, compare=False)
    _doors_by_name: dict[str, Door] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_rooms_by_name", {room.name: room for room in self.rooms})
        object.__setattr__(self, "_doors_by_name", {door.name: door for door in self.doors})
        for door in self.doors:
            for name in door.rooms:
                if name not in self._rooms_by_name:
                    raise ValueError(f"door {door.name} opens into unknown room {name}")
            if door.width <= 2 * self.robot_radius:
                raise ValueError(f"door {door.name} is too narrow for the robot")

    def room(self, name: str) -> Room:
        return self._rooms_by_name[name]

    def door(self, name: str) -> Door:
        return self._doors_by_name[name]

    def room_at(self, position: Point) -> Room | None:
        """The room containing ``position`` (the first one listed, on a shared wall)."""
        for room in self.rooms:
            if room.contains(position):
                return room
        return None

    def doors_of(self, room: str) -> tuple[Door, ...]:
        """The doors opening into ``room``, in the world's order."""
        return tuple(door for door in self.doors if room in door.rooms)

    def obstacle_hit(self, start: Point, end: Point) -> DiscObstacle | None:
        """The first obstacle (in the world's order) the robot touches moving from ``start`` to ``end``."""
        for obstacle in self.obstacles:
            clearance = distance_to_segment(np.asarray(obstacle.center), start, end)
            if clearance < obstacle.radius + self.robot_radius:
                return obstacle
        return None

    def path_hit(self, waypoints: Sequence[Point]) -> tuple[int, DiscObstacle] | None:
        """The first segment of a polyline that touches an obstacle, and the obstacle."""
        for index in range(len(waypoints) - 1):
            hit = self.obstacle_hit(waypoints[index], waypoints[index + 1])
            if hit is not None:
                return index, hit
        return None


def room_name(index: int) -> str:
    """``A``, ``B``, ..., ``Z``, ``AA``, ``AB``, ..."""
    letters = ""
    index += 1
    while index:
        index, remainder = divmod(index - 1, 26)
        letters = chr(ord("A") + remainder) + letters
    return letters


def grid_room_names(rows: int, cols: int) -> list[list[str]]:
    """Room names of a grid, row-major from the top-left corner."""
    return [[room_name(r * cols + c) for c in range(cols)] for r in range(rows)]


def grid_world(
    rows: int,
    cols: int,
    doors: Iterable[tuple[str, str]],
    obstacles: Iterable[DiscObstacle] = (),
    *,
    room_size: float = 1.0,
    door_width: float = 0.36,
    robot_radius: float = 0.06,
) -> RoomsWorld:
    """Square rooms on a ``rows`` x ``cols`` grid (``A`` top-left), doors centred in shared walls.

    ``doors`` lists pairs of grid neighbours; a door is named ``"A-B"``.
    """
    names = grid_room_names(rows, cols)
    cell: dict[str, tuple[int, int]] = {}
    rooms: list[Room] = []
    for r in range(rows):
        for c in range(cols):
            y_min = (rows - 1 - r) * room_size
            rooms.append(Room(names[r][c], c * room_size, y_min, (c + 1) * room_size, y_min + room_size))
            cell[names[r][c]] = (r, c)
    built: list[Door] = []
    for first, second in doors:
        (r1, c1), (r2, c2) = cell[first], cell[second]
        if abs(r1 - r2) + abs(c1 - c2) != 1:
            raise ValueError(f"rooms {first} and {second} are not grid neighbours")
        a, b = sorted((first, second), key=lambda name: cell[name])
        (ra, ca), (rb, cb) = cell[a], cell[b]
        center_x = (ca + cb + 1) / 2 * room_size
        center_y = (rows - (ra + rb + 1) / 2) * room_size
        normal = (1.0, 0.0) if ra == rb else (0.0, -1.0)
        built.append(Door(f"{a}-{b}", (a, b), (center_x, center_y), normal, door_width))
    return RoomsWorld(tuple(rooms), tuple(built), tuple(obstacles), robot_radius)


def crate_in(door: Door, margin: float = 0.03) -> DiscObstacle:
    """A crate that fills ``door``."""
    return DiscObstacle(f"crate in {door.name}", door.center, door.width / 2 + margin, "crate")
