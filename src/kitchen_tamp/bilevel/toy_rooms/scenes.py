"""Toy rooms scenes, each built to show one behaviour, and random instances for benchmarks.

Every scene is deterministic; what varies with a planner's seed is only where
samples land.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.bilevel.problem import BilevelProblem
from kitchen_tamp.bilevel.toy_rooms.domain import Passage, rooms_problem
from kitchen_tamp.bilevel.toy_rooms.world import (
    DiscObstacle,
    Point,
    RoomsWorld,
    crate_in,
    grid_room_names,
    grid_world,
    point,
)


@dataclass(frozen=True)
class RoomsScene:
    """A world, where the robot starts and the room it must reach."""

    name: str
    world: RoomsWorld
    start: tuple[float, float]
    goal_room: str
    description: str

    def problem(self) -> BilevelProblem[Point, Point, str, Passage]:
        return rooms_problem(self.world, point(*self.start), self.goal_room)


def _with_crates(rows: int, cols: int, doors: list[tuple[str, str]], blocked: list[str],
                 pillars: list[DiscObstacle]) -> RoomsWorld:
    plain = grid_world(rows, cols, doors)
    crates = [crate_in(plain.door(name)) for name in blocked]
    return grid_world(rows, cols, doors, [*pillars, *crates])


def open_corridor() -> RoomsScene:
    """Three rooms in a row and nothing in the way: every sample works, greedy refinement succeeds."""
    world = grid_world(1, 3, [("A", "B"), ("B", "C")])
    return RoomsScene("open_corridor", world, (0.3, 0.5), "C", "A -> B -> C, no obstacles")


def pillar_shadow() -> RoomsScene:
    """A pillar just inside door B-C hides it from about two thirds of room B.

    Passing A -> B lands in B's shadow most of the time, and from there B -> C
    fails whatever is sampled: greedy refinement fails for most seeds, while
    backtracking samples A -> B again until it lands in sight of the door.
    """
    world = grid_world(1, 3, [("A", "B"), ("B", "C")], [DiscObstacle("pillar", (1.8, 0.6), 0.08)])
    return RoomsScene("pillar_shadow", world, (0.3, 0.5), "C", "A -> B -> C, a pillar hides door B-C")


def blocked_doorway() -> RoomsScene:
    """The shortest abstract plan A -> B -> C is blocked by a crate in door B-C, which the abstraction
    does not see; the next plan, A -> D -> E -> F -> C, is free. SeSamE switches to it, while
    single-plan refinement fails."""
    doors = [("A", "B"), ("B", "C"), ("A", "D"), ("D", "E"), ("E", "F"), ("C", "F")]
    world = _with_crates(2, 3, doors, ["B-C"], [])
    return RoomsScene("blocked_doorway", world, (0.3, 1.5), "C",
                      "A -> B -> C blocked; A -> D -> E -> F -> C free")


def nine_rooms() -> RoomsScene:
    """A 3 x 3 house from G (bottom left) to C (top right) with a crate in door B-C and a pillar
    shading door C-F: room for abstract BFS to grow its graph."""
    doors = [("A", "B"), ("B", "C"), ("A", "D"), ("D", "E"), ("D", "G"), ("G", "H"),
             ("E", "H"), ("H", "I"), ("E", "F"), ("F", "I"), ("C", "F")]
    world = _with_crates(3, 3, doors, ["B-C"], [DiscObstacle("pillar", (2.4, 1.8), 0.08)])
    return RoomsScene("nine_rooms", world, (0.3, 0.3), "C", "3 x 3 rooms, G to C")


def walled_off() -> RoomsScene:
    """The only way into C is blocked: every planner must fail."""
    world = _with_crates(1, 3, [("A", "B"), ("B", "C")], ["B-C"], [])
    return RoomsScene("walled_off", world, (0.3, 0.5), "C", "A -> B -> C, door B-C blocked")


def no_door_to_goal() -> RoomsScene:
    """Room C has no door at all: there is no abstract plan."""
    world = grid_world(1, 3, [("A", "B")])
    return RoomsScene("no_door_to_goal", world, (0.3, 0.5), "C", "C has no door")


DESIGNED_SCENES = {scene.name: scene for scene in (
    open_corridor(), pillar_shadow(), blocked_doorway(), nine_rooms(), walled_off(), no_door_to_goal())}


def _door_distances(world: RoomsWorld, start: str) -> dict[str, int]:
    distance = {start: 0}
    frontier = deque([start])
    while frontier:
        room = frontier.popleft()
        for door in world.doors_of(room):
            other = door.other_room(room)
            if other not in distance:
                distance[other] = distance[room] + 1
                frontier.append(other)
    return distance


def random_scene(
    seed: int,
    *,
    extra_door_probability: float = 0.35,
    crate_probability: float = 0.12,
    pillar_probability: float = 0.6,
) -> RoomsScene:
    """A random house of 3 x 3 to 4 x 4 rooms.

    Doors: a random spanning tree of the grid plus each other neighbouring pair
    with ``extra_door_probability``. Each door holds a crate with
    ``crate_probability``; each room has, with ``pillar_probability``, a pillar a
    little in front of one of its doors, which hides that door from part of the room.
    The robot starts at a random free point and must reach the room farthest
    from it by doors. Not every instance is solvable.
    """
    rng = np.random.default_rng(seed)
    rows, cols = int(rng.integers(3, 5)), int(rng.integers(3, 5))
    names = grid_room_names(rows, cols)
    cells = [(r, c) for r in range(rows) for c in range(cols)]
    neighbours = [((r, c), (r + dr, c + dc)) for r, c in cells for dr, dc in ((0, 1), (1, 0))
                  if r + dr < rows and c + dc < cols]
    connected = {cells[int(rng.integers(len(cells)))]}
    tree: set[tuple[tuple[int, int], tuple[int, int]]] = set()
    while len(connected) < len(cells):
        crossing = [pair for pair in neighbours if (pair[0] in connected) != (pair[1] in connected)]
        pair = crossing[int(rng.integers(len(crossing)))]
        tree.add(pair)
        connected.update(pair)
    chosen = [pair for pair in neighbours if pair in tree or rng.random() < extra_door_probability]
    doors = [(names[a[0]][a[1]], names[b[0]][b[1]]) for a, b in chosen]
    plain = grid_world(rows, cols, doors)
    obstacles: list[DiscObstacle] = []
    for room in plain.rooms:
        if rng.random() < pillar_probability:
            room_doors = plain.doors_of(room.name)
            door = room_doors[int(rng.integers(len(room_doors)))]
            approach = door.point_inside(room.name, plain.robot_radius)
            inward = door.point_inside(room.name, 1.0) - door.point_inside(room.name, 0.0)
            sideways = np.array([inward[1], -inward[0]])
            radius = float(rng.uniform(0.05, 0.09))
            distance = radius + plain.robot_radius + float(rng.uniform(0.03, 0.15))
            angle = float(rng.uniform(-1.0, 1.0))
            center = approach + distance * (np.cos(angle) * inward + np.sin(angle) * sideways)
            position = (float(center[0]), float(center[1]))
            obstacles.append(DiscObstacle(f"pillar in {room.name}", position, radius))
    obstacles += [crate_in(door) for door in plain.doors if rng.random() < crate_probability]
    world = grid_world(rows, cols, doors, obstacles)
    start_room = plain.rooms[int(rng.integers(len(plain.rooms)))]
    while True:
        start = start_room.sample_point(rng, 0.15)
        if world.obstacle_hit(start, start) is None:
            break
    distances = _door_distances(world, start_room.name)
    farthest = max(distances.values())
    goals = sorted(room for room, d in distances.items() if d == farthest)
    goal = goals[int(rng.integers(len(goals)))]
    return RoomsScene(f"random_{seed}", world, (float(start[0]), float(start[1])), goal,
                      f"{rows} x {cols} rooms, {len(doors)} doors, {len(obstacles)} obstacles")
