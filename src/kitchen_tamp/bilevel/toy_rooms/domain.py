"""The toy rooms domain as a bilevel problem.

* low-level state x: the robot's position (a numpy array: not hashable, on purpose);
* low-level action u: a displacement, x' = x + u;
* abstract state s: the name of the room the robot is in, Psi(x) = that room;
* abstract action a: a :class:`Passage` through one door into the neighbouring room;
* goal: being in the goal room.

The sampler of a passage drives straight to the doorway, straight through it,
and straight to a point drawn uniformly in the next room. The straight line to
the doorway is fixed by where the robot stands, so a pillar can hide a doorway
from part of a room: a landing point there makes the *next* passage impossible.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.bilevel.abstraction import Abstraction, AbstractTransition
from kitchen_tamp.bilevel.problem import BilevelProblem, SamplingFailure, TrajectorySampler
from kitchen_tamp.bilevel.toy_rooms.world import DiscObstacle, Point, RoomsWorld
from kitchen_tamp.bilevel.trajectory import Trajectory, rollout

LANDING_MARGIN = 0.05
"""Extra distance (beyond the robot's radius) that landing points keep from the walls."""


@dataclass(frozen=True)
class Passage:
    """Go from ``source_room`` through ``door`` into ``target_room``."""

    door: str
    source_room: str
    target_room: str

    def __str__(self) -> str:
        return f"go {self.source_room}->{self.target_room}"


class BlockedPath(SamplingFailure):
    """Segment ``segment`` of the sampled path ``waypoints`` touches ``obstacle``."""

    def __init__(
        self, message: str, waypoints: tuple[Point, ...], segment: int, obstacle: DiscObstacle
    ) -> None:
        super().__init__(message)
        self.waypoints = waypoints
        self.segment = segment
        self.obstacle = obstacle


def move(state: Point, displacement: Point) -> Point:
    """The transition function: x' = x + u."""
    return state + displacement


def _text(position: Point) -> str:
    return f"({position[0]:.2f}, {position[1]:.2f})"


class PassageSampler:
    """Samples a trajectory for any passage of ``world``: doorway, through it, a random landing point."""

    def __init__(self, world: RoomsWorld) -> None:
        self.world = world

    def __call__(
        self, state: Point, transition: AbstractTransition[str, Passage], rng: np.random.Generator
    ) -> Trajectory[Point, Point]:
        passage = transition.action
        door = self.world.door(passage.door)
        depth = self.world.robot_radius
        landing = self.world.room(passage.target_room).sample_point(rng, depth + LANDING_MARGIN)
        waypoints = (state, door.point_inside(passage.source_room, depth),
                     door.point_inside(passage.target_room, depth), landing)
        hit = self.world.path_hit(waypoints)
        if hit is not None:
            segment, obstacle = hit
            what = (f"the way from {_text(state)} to door {door.name}",
                    f"door {door.name}",
                    f"the way from door {door.name} to {_text(landing)}")[segment]
            raise BlockedPath(f"{what} is blocked by {obstacle.name}", waypoints, segment, obstacle)
        displacements = [waypoints[i + 1] - waypoints[i] for i in range(len(waypoints) - 1)]
        return rollout(move, state, displacements)


def rooms_abstraction(world: RoomsWorld, goal_room: str) -> Abstraction[Point, str, Passage]:
    """Psi(x) = the room x is in; successors = the passages through the room's doors."""

    def abstract_state(state: Point) -> str:
        room = world.room_at(state)
        if room is None:
            raise ValueError(f"position {_text(state)} is outside every room")
        return room.name

    def successors(room: str) -> Iterator[tuple[Passage, str]]:
        for door in world.doors_of(room):
            target = door.other_room(room)
            yield Passage(door.name, room, target), target

    return Abstraction(abstract_state, successors, lambda room: room == goal_room, describe=str)


def rooms_problem(
    world: RoomsWorld, start: Point, goal_room: str
) -> BilevelProblem[Point, Point, str, Passage]:
    """The bilevel problem of driving from ``start`` into ``goal_room``."""
    sampler: TrajectorySampler[Point, Point, str, Passage] = PassageSampler(world)
    return BilevelProblem(
        initial_state=start,
        abstraction=rooms_abstraction(world, goal_room),
        sampler_for=lambda passage: sampler,
        transition=move,
    )
