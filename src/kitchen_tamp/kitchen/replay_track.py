"""One segment as the judge replayed it: its states and, per state, what the hand holds (a box
riding with it, or a drawer by its handle) and every drawer's opening.

Tracks are what both judges read: the kinematic judge derives them
(``kitchen_tamp.kitchen.action_replay``), pictures pose the kitchen from them,
and execution under physics commands the grip and compares the simulated scene
with them, so the two judges mean the same plan.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment, SegmentSamples
from kitchen_tamp.world import FloatArray, Pose

IndexArray = npt.NDArray[np.intp]


@dataclass(frozen=True)
class Carried:
    """A box riding with the hand at ``hand_from_box``, taken with the fingers ``width`` apart."""

    box: str
    hand_from_box: Pose
    width: float


@dataclass(frozen=True)
class Gripped:
    """A drawer held by its handle, taken with the fingers ``width`` apart when the tool was at
    ``world_from_tool`` and the drawer open ``opening_start``; it moves along ``axis``."""

    drawer: str
    width: float
    world_from_tool: Pose
    opening_start: float
    axis: FloatArray


@dataclass(frozen=True, eq=False)
class SegmentTrack:
    """One segment as replayed: its states and, per state, the box riding with the hand, the
    drawer whose handle the fingers hold, and every drawer's opening."""

    segment: Segment
    samples: SegmentSamples
    carried: tuple[Carried | None, ...]
    gripped: tuple[str | None, ...]
    openings: Mapping[str, FloatArray]

    def __len__(self) -> int:
        return len(self.samples)

    def holds(self, index: int) -> bool:
        """Whether the fingers hold something (a box or a handle) in state ``index``."""
        return self.carried[index] is not None or self.gripped[index] is not None

    def states_at(self, intervals: IndexArray, fractions: FloatArray) -> IndexArray:
        """Per (waypoint interval, fraction of the way along it): the replayed state nearest that
        point (states of an interval are evenly spaced after its first waypoint)."""
        owners = self.samples.waypoint_of
        start = owners.searchsorted(intervals, side="left")
        end = owners.searchsorted(intervals, side="right")
        # the interval's states are at fractions 1/count ... 1 after the state of its first
        # waypoint (state 0 is the first waypoint itself and also lies in interval 0)
        base = np.where(intervals == 0, 0, start - 1)
        count = end - 1 - base
        return base + np.round(np.clip(fractions, 0.0, 1.0) * count).astype(np.intp)

    def pose(self, kitchen: KitchenScene, index: int) -> None:
        """Put ``kitchen`` (replayed up to the state before) in state ``index``."""
        for drawer, values in self.openings.items():
            if kitchen.opening(drawer) != float(values[index]):
                kitchen.set_opening(drawer, float(values[index]))
        kitchen.robot.set_gripper_width(float(self.samples.gripper_widths[index]))
        kitchen.robot.set_configuration(self.samples.configurations[index])
        wanted, held = self.carried[index], kitchen.held_box()
        if held is not None and (wanted is None or wanted.box != held):
            kitchen.release(held)
        if wanted is not None and held != wanted.box:
            take(kitchen, wanted)


def take(kitchen: KitchenScene, carried: Carried) -> None:
    """Make ``carried.box`` ride with the hand at its pose relative to the hand."""
    body = kitchen.box(carried.box)
    kitchen.scene.detach(body)
    world_from_hand = kitchen.robot.body.link_pose(kitchen.robot.description.hand_link)
    kitchen.scene.set_base_pose(body, world_from_hand @ carried.hand_from_box)
    kitchen.grasp(carried.box)

