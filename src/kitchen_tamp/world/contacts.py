"""Closest points between two links, and bodies of a scene that overlap: the geometry queries
the judge uses to find what the fingers touch and whether a layout interpenetrates."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pybullet as p

from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray


@dataclass(frozen=True, eq=False)
class ClosestPoints:
    """The closest points of two links: signed distance (m) and a witness point on each."""

    distance: float
    on_first: FloatArray
    on_second: FloatArray


def closest_points(
    first: Body, first_link: int, second: Body, second_link: int, horizon: float
) -> ClosestPoints | None:
    """The nearest pair of points of the two links if they are within ``horizon``, else None."""
    found = p.getClosestPoints(
        first.uid, second.uid, horizon, first_link, second_link, physicsClientId=first.client
    )
    if not found:
        return None
    nearest = min(found, key=lambda c: c[8])
    return ClosestPoints(float(nearest[8]), np.asarray(nearest[5]), np.asarray(nearest[6]))


@dataclass(frozen=True)
class Overlap:
    """Two bodies' links that interpenetrate by ``depth`` (m)."""

    first: str
    second: str
    depth: float


def overlapping_links(scene: Scene, depth: float) -> list[Overlap]:
    """Links of different bodies that interpenetrate deeper than ``depth``, each pair once
    with its deepest penetration, in load order of the bodies."""
    bodies = scene.bodies
    deepest: dict[tuple[str, str], float] = {}
    for i, first in enumerate(bodies):
        for second in bodies[i + 1 :]:
            for contact in p.getClosestPoints(first.uid, second.uid, 0.0, physicsClientId=first.client):
                if contact[8] < -depth:
                    key = (
                        f"{first.name}/{first.link_name(contact[3])}",
                        f"{second.name}/{second.link_name(contact[4])}",
                    )
                    deepest[key] = max(deepest.get(key, 0.0), -float(contact[8]))
    return [Overlap(a, b, d) for (a, b), d in deepest.items()]
