"""The toy rooms domain written as PDDL, to exercise the relational adapter.

Abstract states become sets of ``(in ROOM)`` atoms and abstract actions
ground ``go`` operators; the trajectory sampler is the rooms domain's own,
handed a :class:`~kitchen_tamp.bilevel.toy_rooms.domain.Passage` made from the
ground action's arguments.
"""

from __future__ import annotations

import numpy as np

from kitchen_tamp.bilevel.abstraction import AbstractTransition
from kitchen_tamp.bilevel.problem import BilevelProblem
from kitchen_tamp.bilevel.relational import relational_problem, samplers_by_operator
from kitchen_tamp.bilevel.toy_rooms.domain import Passage, PassageSampler, move
from kitchen_tamp.bilevel.toy_rooms.scenes import RoomsScene
from kitchen_tamp.bilevel.toy_rooms.world import Point, point
from kitchen_tamp.bilevel.trajectory import Trajectory
from kitchen_tamp.planning import Atom, GroundAction, State, Task

ROOMS_DOMAIN = """\
(define (domain rooms)
  (:requirements :strips :typing)
  (:types room door)
  (:predicates (in ?r - room) (connects ?d - door ?from - room ?to - room))
  (:action go
    :parameters (?d - door ?from - room ?to - room)
    :precondition (and (in ?from) (connects ?d ?from ?to))
    :effect (and (not (in ?from)) (in ?to))))
"""


def rooms_problem_pddl(scene: RoomsScene) -> str:
    """The PDDL problem of ``scene``: rooms and doors as objects, the start room, the goal room."""
    world = scene.world
    start_room = world.room_at(point(*scene.start))
    if start_room is None:
        raise ValueError(f"scene {scene.name} starts outside every room")
    connections = [f"(connects {door.name} {a} {b})"
                   for door in world.doors for a, b in (door.rooms, door.rooms[::-1])]
    return "\n".join([
        f"(define (problem {scene.name.replace('_', '-')})",
        "  (:domain rooms)",
        f"  (:objects {' '.join(room.name for room in world.rooms)} - room",
        f"            {' '.join(door.name for door in world.doors)} - door)",
        f"  (:init (in {start_room.name})",
        *(f"         {fact}" for fact in connections),
        "  )",
        f"  (:goal (in {scene.goal_room})))",
        "",
    ])


class GoActionSampler:
    """Samples a ground ``go ?d ?from ?to`` action with the rooms domain's passage sampler."""

    def __init__(self, scene: RoomsScene) -> None:
        self.passages = PassageSampler(scene.world)

    def __call__(
        self, state: Point, transition: AbstractTransition[State, GroundAction], rng: np.random.Generator
    ) -> Trajectory[Point, Point]:
        door, source, target = transition.action.args
        passage = Passage(door, source, target)
        return self.passages(state, AbstractTransition(source, passage, target), rng)


def relational_rooms_problem(
    scene: RoomsScene, task: Task
) -> BilevelProblem[Point, Point, State, GroundAction]:
    """``scene`` as a relational bilevel problem over ``task`` (the grounded :func:`rooms_problem_pddl`)."""
    world = scene.world

    def atoms_of(state: Point) -> set[Atom]:
        room = world.room_at(state)
        return set() if room is None else {("in", room.name)}

    return relational_problem(task, point(*scene.start), atoms_of,
                              samplers_by_operator({"go": GoActionSampler(scene)}), transition=move)
