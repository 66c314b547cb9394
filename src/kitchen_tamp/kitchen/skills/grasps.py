"""Grasps computed from geometry: parallel-jaw grasps of a box and of a drawer handle.

The tool frame sits between the finger pads; its z axis is the approach (from
the hand into the object) and its y axis the direction the fingers close along.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.world import FloatArray, Pose


@dataclass(frozen=True)
class Grasp:
    """Where the tool holds an object, in the object's frame, and how wide the fingers close."""

    object_from_tool: Pose
    width: float
    kind: str

    def __post_init__(self) -> None:
        if self.width <= 0.0:
            raise ValueError(f"grasp width must be positive, got {self.width}")

    @property
    def tool_from_object(self) -> Pose:
        """The object's pose in the tool frame."""
        return self.object_from_tool.inverse()

    def approach_in_object(self) -> FloatArray:
        """Unit approach direction (tool z) in the object frame."""
        return np.asarray(self.object_from_tool.rotation[:, 2])


def tool_rotation(approach: FloatArray, closing: FloatArray) -> FloatArray:
    """Rotation whose z is ``approach`` and y is ``closing`` (both unit, orthogonal)."""
    z = approach / np.linalg.norm(approach)
    y = closing - np.dot(closing, z) * z
    y = y / np.linalg.norm(y)
    return np.column_stack([np.cross(y, z), y, z])


def box_grasp_families(size: tuple[float, float, float], max_width: float) -> list[tuple[int, int, int]]:
    """(approach axis, approach sign, closing axis) of every face grasp whose width fits.

    The hand comes from the side of the box where the approach axis has the given
    sign and closes across ``closing axis``.
    """
    families = []
    for axis in range(3):
        for sign in (-1, 1):
            for closing in range(3):
                if closing != axis and size[closing] <= max_width:
                    families.append((axis, sign, closing))
    return families


def sample_box_grasp(
    size: tuple[float, float, float],
    world_from_box: Pose,
    rng: np.random.Generator,
    max_width: float,
    parameters: SkillParameters,
) -> Grasp | None:
    """A random face grasp of a box, or None if the box fits no grasp.

    Grasps whose approach points upwards in the world (the hand under the box)
    are not produced: the hand comes from above or from the side.
    """
    families = [
        f
        for f in box_grasp_families(size, max_width)
        if (world_from_box.rotation @ (-f[1] * np.eye(3)[f[0]]))[2] <= 0.1
    ]
    if not families:
        return None
    axis, sign, closing = families[int(rng.integers(len(families)))]
    free = 3 - axis - closing
    approach = -sign * np.eye(3)[axis]
    closing_direction = np.eye(3)[closing] * (1.0 if rng.random() < 0.5 else -1.0)
    depth = rng.uniform(*parameters.grasp_depth)
    depth = min(depth, size[axis] / 2.0)
    slack = max(0.0, size[free] / 2.0 - parameters.finger_pad_half_width)
    position = sign * np.eye(3)[axis] * (size[axis] / 2.0 - depth)
    position = position + np.eye(3)[free] * rng.uniform(-slack, slack)
    kind = "top" if (world_from_box.rotation @ approach)[2] < -0.9 else "side"
    return Grasp(
        Pose.from_rotation(position, tool_rotation(approach, closing_direction)), size[closing], kind
    )


def sample_handle_grasp(
    world_from_bar: Pose,
    bar_size: tuple[float, float, float],
    pull_direction: FloatArray,
    free_half_length: float,
    rng: np.random.Generator,
) -> tuple[Pose, float]:
    """(world_from_tool, width) of a grasp on a handle bar, approaching against the pull.

    The fingers close across the bar's thinnest side perpendicular to the pull;
    the tool slides along the bar within ``free_half_length`` of its centre.
    """
    approach = -pull_direction / np.linalg.norm(pull_direction)
    rotation = world_from_bar.rotation
    long_axis = int(np.argmax(bar_size))
    across = [i for i in range(3) if i != long_axis]
    closing_axis = min(across, key=lambda i: abs(float(np.dot(rotation[:, i], approach))))
    closing = rotation[:, closing_axis] * (1.0 if rng.random() < 0.5 else -1.0)
    offset = rotation[:, long_axis] * rng.uniform(-free_half_length, free_half_length)
    position = world_from_bar.translation + offset
    return Pose.from_rotation(position, tool_rotation(approach, closing)), float(bar_size[closing_axis])
