"""A small 2-D domain for the bilevel planners: a disc robot driving through rooms and doorways.

Abstract states are "in room R"; pillars can hide a doorway from part of a room
and crates can block a doorway, neither of which the abstraction sees. Used by
the tests, the ``examples/`` pictures and ``benchmarks/bilevel.py``.
"""

from kitchen_tamp.bilevel.toy_rooms.domain import (
    BlockedPath,
    Passage,
    PassageSampler,
    move,
    rooms_abstraction,
    rooms_problem,
)
from kitchen_tamp.bilevel.toy_rooms.relational_rooms import (
    ROOMS_DOMAIN,
    relational_rooms_problem,
    rooms_problem_pddl,
)
from kitchen_tamp.bilevel.toy_rooms.scenes import (
    DESIGNED_SCENES,
    RoomsScene,
    blocked_doorway,
    nine_rooms,
    no_door_to_goal,
    open_corridor,
    pillar_shadow,
    random_scene,
    walled_off,
)
from kitchen_tamp.bilevel.toy_rooms.world import (
    DiscObstacle,
    Door,
    Point,
    Room,
    RoomsWorld,
    crate_in,
    grid_world,
    point,
)

__all__ = [
    "DESIGNED_SCENES",
    "ROOMS_DOMAIN",
    "BlockedPath",
    "DiscObstacle",
    "Door",
    "Passage",
    "PassageSampler",
    "Point",
    "Room",
    "RoomsScene",
    "RoomsWorld",
    "blocked_doorway",
    "crate_in",
    "grid_world",
    "move",
    "nine_rooms",
    "no_door_to_goal",
    "open_corridor",
    "pillar_shadow",
    "point",
    "random_scene",
    "relational_rooms_problem",
    "rooms_abstraction",
    "rooms_problem",
    "rooms_problem_pddl",
    "walled_off",
]
