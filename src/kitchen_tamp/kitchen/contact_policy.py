"""Which contacts an action means, what the fingers hold, what a loose box stands on, and
whether a layout overlaps.

An action may touch only its own objects, and only down to
``CONTACT_PENETRATION_BOUND``: the fingers on a box it names, a box it names
on the support it names (the surface's link, or the drawer's floor and walls),
and -- for an action that names a drawer and no box, i.e. opens it -- the
gripper on that drawer's handle. Every other contact is a collision.

The fingers hold an object when both touch it (within ``TOUCH_DISTANCE``) from
opposite sides: what each finger touches lies between the two fingers, the
left finger's point left of the right finger's.

A loose box is supported when it rests on something as Ψ means it (a surface, a
region, a drawer's floor, another box's top face: centre over its face, lowest
corner on it) and stands upright (tilted at most ``SUPPORT_TILT_DEG``); a box
that is not supported falls.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.abstraction import supports_of
from kitchen_tamp.kitchen.errors import UnsupportedInitialStateError
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.world import BASE_LINK, AllowedContact, Body
from kitchen_tamp.world.collision.checked_pairs import CONTACT_PENETRATION_BOUND
from kitchen_tamp.world.contacts import closest_points, overlapping_links

__all__ = [
    "CONTACT_PENETRATION_BOUND",
    "SUPPORT_TILT_DEG",
    "TOUCH_DISTANCE",
    "HeldObject",
    "check_initial_overlaps",
    "finger_distance",
    "fingers_holding",
    "intended_contacts",
    "support_of",
]

TOUCH_DISTANCE: Final = 0.001
"""A finger touches an object when their shapes are at most this far apart (m)."""
SUPPORT_TILT_DEG: Final = 5.0
"""A box stands on a region when its axis nearest the vertical is at most this far from it."""


def _support_links(kitchen: KitchenScene, support: str) -> tuple[str, ...]:
    if support in kitchen.map.surfaces:
        return (kitchen.map.surfaces[support].link,)
    symbol = kitchen.map.openables[support]
    return (symbol.floor_link, symbol.link)


def intended_contacts(kitchen: KitchenScene, args: Sequence[str]) -> tuple[AllowedContact, ...]:
    """The contacts an action with these arguments means, each bounded in depth."""
    types = {arg: kitchen.map.type_of(arg) for arg in args}
    boxes = [a for a in args if types[a] == "box"]
    supports = [a for a in args if types[a] in ("surface", "openable")]
    contacts = [kitchen.finger_contact(box) for box in boxes]
    for box in boxes:
        for support in supports:
            contacts += [
                AllowedContact(kitchen.kitchen.name, link, carried=box)
                for link in _support_links(kitchen, support)
            ]
    if not boxes:
        contacts += [kitchen.handle_contact(a) for a in args if types[a] == "openable"]
    return tuple(contacts)


@dataclass(frozen=True)
class HeldObject:
    """What closed fingers hold: a box, or a drawer by its handle."""

    kind: str
    """``box`` or ``handle``."""
    name: str
    """The box, or the drawer whose handle it is."""


def _touch_points(kitchen: KitchenScene, body: Body, link: int) -> list[np.ndarray] | None:
    """Where each finger (in a fixed order) touches ``body``'s link, or None if one does not."""
    robot = kitchen.robot
    points = []
    for finger in sorted(robot.finger_links):
        found = closest_points(robot.body, robot.body.link_index(finger), body, link, TOUCH_DISTANCE)
        if found is None:
            return None
        points.append(found.on_second)
    return points


def _between_fingers(kitchen: KitchenScene, points: list[np.ndarray]) -> bool:
    robot = kitchen.robot
    first, second = (robot.body.link_pose(f).translation for f in sorted(robot.finger_links))
    return float(np.dot(points[1] - points[0], second - first)) > 0.0


def fingers_holding(kitchen: KitchenScene, boxes: Sequence[str], drawers: Sequence[str]) -> HeldObject | None:
    """The first of ``boxes`` (then of ``drawers``' handles) the fingers hold now, or None."""
    for box in boxes:
        points = _touch_points(kitchen, kitchen.box(box), BASE_LINK)
        if points is not None and _between_fingers(kitchen, points):
            return HeldObject("box", box)
    for drawer in drawers:
        handle = kitchen.kitchen.link_index(kitchen.map.openables[drawer].handle_link)
        points = _touch_points(kitchen, kitchen.kitchen, handle)
        if points is not None and _between_fingers(kitchen, points):
            return HeldObject("handle", drawer)
    return None


def finger_distance(kitchen: KitchenScene, box: str) -> float:
    """How far (m) the nearer finger is from ``box``."""
    robot = kitchen.robot
    distances = [
        found.distance
        for finger in robot.finger_links
        if (
            found := closest_points(
                robot.body, robot.body.link_index(finger), kitchen.box(box), BASE_LINK, 10.0
            )
        )
    ]
    return min(distances, default=float("inf"))


def support_of(kitchen: KitchenScene, box: str) -> str | None:
    """What ``box`` stands on now -- a surface, a region, a drawer's floor or another box, as Ψ
    finds it (``abstraction.supports_of``) -- provided it stands upright; else None."""
    rotation = kitchen.box(box).base_pose().rotation
    upright = float(np.max(np.abs(rotation[2, :])))
    if upright < np.cos(np.radians(SUPPORT_TILT_DEG)):
        return None
    supports = supports_of(kitchen, box)
    return supports[0][1] if supports else None


def check_initial_overlaps(kitchen: KitchenScene) -> None:
    """Raise ``UnsupportedInitialStateError`` naming the bodies when two bodies of the laid-out
    kitchen overlap deeper than the contact bound (a box through the counter, two boxes in
    one place, a box in the robot)."""
    overlaps = overlapping_links(kitchen.scene, CONTACT_PENETRATION_BOUND)
    if overlaps:
        listed = ", ".join(f"{o.first} and {o.second} ({o.depth * 1000:.0f} mm)" for o in overlaps)
        raise UnsupportedInitialStateError(f"the problem's :init lays out overlapping bodies: {listed}")
