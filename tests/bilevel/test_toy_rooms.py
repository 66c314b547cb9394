"""The toy rooms domain itself: geometry, the passage sampler and the random instances."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.bilevel import AbstractTransition, SamplingFailure
from kitchen_tamp.bilevel.toy_rooms import (
    BlockedPath,
    DiscObstacle,
    Passage,
    PassageSampler,
    crate_in,
    grid_world,
    point,
    random_scene,
    rooms_abstraction,
)


def test_grid_rooms_and_doors_sit_where_the_grid_says() -> None:
    world = grid_world(2, 2, [("A", "B"), ("A", "C")])
    assert [room.name for room in world.rooms] == ["A", "B", "C", "D"]
    assert world.room_at(point(0.5, 1.5)) == world.room("A")
    assert world.room_at(point(1.5, 0.5)) == world.room("D")
    assert world.door("A-B").center == (1.0, 1.5)
    assert world.door("A-C").center == (0.5, 1.0)
    assert world.door("A-C").point_inside("C", 0.1)[1] == pytest.approx(0.9)
    with pytest.raises(ValueError, match="not grid neighbours"):
        grid_world(2, 2, [("A", "D")])


def test_the_abstraction_sees_rooms_and_doors_not_obstacles() -> None:
    plain = grid_world(1, 2, [("A", "B")])
    world = grid_world(1, 2, [("A", "B")], [crate_in(plain.door("A-B"))])
    abstraction = rooms_abstraction(world, "B")
    assert abstraction.abstract_state(point(0.2, 0.5)) == "A"
    assert list(abstraction.successors("A")) == [(Passage("A-B", "A", "B"), "B")]
    assert abstraction.is_goal("B") and not abstraction.is_goal("A")


def test_a_passage_lands_in_the_next_room_clear_of_obstacles() -> None:
    world = grid_world(1, 2, [("A", "B")], [DiscObstacle("pillar", (1.5, 0.5), 0.1)])
    sampler = PassageSampler(world)
    transition = AbstractTransition("A", Passage("A-B", "A", "B"), "B")
    rng = np.random.default_rng(0)
    landed = 0
    for _ in range(50):
        try:
            trajectory = sampler(point(0.3, 0.3), transition, rng)
        except BlockedPath as blocked:
            assert "pillar" in str(blocked) and len(blocked.waypoints) == 4
            continue
        landed += 1
        assert world.room_at(trajectory.final_state) == world.room("B")
        assert world.path_hit(trajectory.states) is None
    assert 0 < landed < 50


def test_a_crate_blocks_its_doorway_for_every_sample() -> None:
    plain = grid_world(1, 2, [("A", "B")])
    world = grid_world(1, 2, [("A", "B")], [crate_in(plain.door("A-B"))])
    sampler = PassageSampler(world)
    transition = AbstractTransition("A", Passage("A-B", "A", "B"), "B")
    rng = np.random.default_rng(0)
    for _ in range(10):
        with pytest.raises(SamplingFailure, match="crate in A-B"):
            sampler(point(0.3, 0.5), transition, rng)


def test_random_scenes_are_deterministic_and_start_inside_a_free_room() -> None:
    for seed in range(20):
        scene = random_scene(seed)
        assert scene == random_scene(seed)
        start = point(*scene.start)
        assert scene.world.room_at(start) is not None
        assert scene.world.obstacle_hit(start, start) is None
        assert scene.goal_room in {room.name for room in scene.world.rooms}
    assert len({random_scene(seed).world for seed in range(5)}) > 1
