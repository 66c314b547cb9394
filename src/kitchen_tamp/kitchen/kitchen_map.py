"""What each symbol of the kitchen domain is in the scene: bodies, links, joints, models.

This replaces the original project's table of hand-tuned joint angles: a symbol
maps to geometry (a surface link, a drawer's joint, floor and handle links, a
box model) and every joint goal is computed from that geometry.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Final

MODELS_DIR: Final = Path(__file__).resolve().parents[3] / "models"
KITCHEN_URDF: Final = MODELS_DIR / "kitchen.urdf"

KITCHEN_BODY: Final = "kitchen"
ROBOT_BODY: Final = "panda"
ROBOT_MOUNT_LINK: Final = "robot_mount"
"""The robot's base stands at the centre of this link's top face."""


@dataclass(frozen=True)
class SurfaceSymbol:
    """A ``surface``: a box link of the kitchen whose top face boxes stand on."""

    link: str


@dataclass(frozen=True)
class OpenableSymbol:
    """An ``openable``: a tray on a prismatic joint, its floor and its handle links."""

    joint: str
    link: str
    floor_link: str
    handle_link: str
    opened_fraction: float = 0.5
    """``opened`` holds when the joint is beyond this fraction of its travel."""


@dataclass(frozen=True)
class BoxSymbol:
    """A ``box``: a rigid box body loaded from its own URDF."""

    urdf: Path


@dataclass(frozen=True)
class KitchenMap:
    """Symbol -> geometry for every object the kitchen has, grouped by PDDL type."""

    surfaces: MappingProxyType[str, SurfaceSymbol] = field(
        default_factory=lambda: MappingProxyType(
            {"stove": SurfaceSymbol("stove"), "countertop": SurfaceSymbol("countertop")}
        )
    )
    openables: MappingProxyType[str, OpenableSymbol] = field(
        default_factory=lambda: MappingProxyType(
            {"drawer": OpenableSymbol("drawer_joint", "drawer", "drawer_floor", "drawer_handle")}
        )
    )
    boxes: MappingProxyType[str, BoxSymbol] = field(
        default_factory=lambda: MappingProxyType(
            {
                "sugar": BoxSymbol(MODELS_DIR / "sugar.urdf"),
                "spam": BoxSymbol(MODELS_DIR / "spam.urdf"),
                "baguette": BoxSymbol(MODELS_DIR / "baguette.urdf"),
            }
        )
    )

    def type_of(self, name: str) -> str | None:
        """The PDDL type of a kitchen object, or None if the kitchen has no such object."""
        if name in self.surfaces:
            return "surface"
        if name in self.openables:
            return "openable"
        if name in self.boxes:
            return "box"
        return None


KITCHEN_MAP: Final = KitchenMap()
