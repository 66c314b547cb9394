"""What a geometry model reads of a scene: plain names, URDF paths, poses and checked pairs.

`kitchen_tamp.world.scene_description.SceneDescription` is one such scene, made
from a PyBullet scene; the models of `motion.geometry` (Drake's and the sphere
model) read it through these protocols, so motion never imports the PyBullet side
and any other source of scenes (a benchmark's obstacle list) can feed them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Protocol

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

DEFAULT_DISTANCE_HORIZON = 0.1
"""Pairs further apart than this (m) are not measured by a model's signed distances; distances
are capped here."""


class DescribedBody(Protocol):
    """One URDF body of the scene (see `kitchen_tamp.world.scene_description.BodyDescription`)."""

    @property
    def name(self) -> str: ...
    @property
    def urdf_path(self) -> str: ...
    @property
    def base_link(self) -> str: ...
    @property
    def world_from_base(self) -> FloatArray: ...
    @property
    def joint_positions(self) -> Mapping[str, float]: ...


class DescribedAttachment(Protocol):
    """Body ``child`` welded to ``parent``'s link at ``parent_link_from_child`` (4, 4)."""

    @property
    def parent(self) -> str: ...
    @property
    def parent_link(self) -> str: ...
    @property
    def child(self) -> str: ...
    @property
    def parent_link_from_child(self) -> FloatArray: ...


class DescribedPair(Protocol):
    """A checked link pair (see `kitchen_tamp.world.collision.checked_pairs.CheckedLinkPair`)."""

    @property
    def body_a(self) -> str: ...
    @property
    def link_a(self) -> str: ...
    @property
    def body_b(self) -> str: ...
    @property
    def link_b(self) -> str: ...
    @property
    def allowance(self) -> float: ...


class DescribedScene(Protocol):
    """A scene snapshot (see `kitchen_tamp.world.scene_description.SceneDescription`)."""

    @property
    def bodies(self) -> Sequence[DescribedBody]: ...
    @property
    def attachments(self) -> Sequence[DescribedAttachment]: ...
    @property
    def robot(self) -> str: ...
    @property
    def arm_joints(self) -> Sequence[str]: ...
    @property
    def arm_lower(self) -> FloatArray: ...
    @property
    def arm_upper(self) -> FloatArray: ...
    @property
    def gripper_links(self) -> frozenset[str]: ...
    @property
    def checked_pairs(self) -> Sequence[DescribedPair]: ...
