"""What a motion planner returns: a status, the path if any, and search counts."""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.motion.collision_checker import JointConfiguration
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker


class PlanStatus(enum.Enum):
    """Outcome of a motion-planning query."""

    SOLVED = "solved"
    START_IN_COLLISION = "start in collision"
    GOAL_IN_COLLISION = "goal in collision"
    ITERATION_LIMIT = "iteration limit reached"
    TIME_LIMIT = "time budget exhausted"


class MotionPlanningError(Exception):
    """A motion-planning query has no path; `status` says why."""

    def __init__(self, status: PlanStatus, message: str) -> None:
        super().__init__(message)
        self.status = status


@dataclass(frozen=True, eq=False)
class PlanningResult:
    """A planner's answer. `path` is (m, d) with path[0] == start, path[-1] == goal.

    Counts are kept on failure too: `iterations` of the main loop, `nodes` in
    the search tree(s), `collision_checks` = configurations handed to the
    checker, `planning_time_s` wall-clock seconds.
    """

    status: PlanStatus
    path: JointPath | None
    iterations: int
    nodes: int
    collision_checks: int
    planning_time_s: float

    def __post_init__(self) -> None:
        if (self.status is PlanStatus.SOLVED) != (self.path is not None):
            raise ValueError(f"a path comes with status SOLVED only, got {self.status}")

    @property
    def solved(self) -> bool:
        """Whether a path was found."""
        return self.status is PlanStatus.SOLVED

    def require_path(self) -> JointPath:
        """The path, or raise `MotionPlanningError` naming the status and counts."""
        if self.path is None:
            raise MotionPlanningError(
                self.status,
                f"no path: {self.status.value} after {self.iterations} iterations, "
                f"{self.nodes} nodes, {self.collision_checks} collision checks",
            )
        return self.path


def endpoint_collision_status(
    checker: CountingSegmentChecker, start: JointConfiguration, goal: JointConfiguration
) -> PlanStatus | None:
    """START_IN_COLLISION or GOAL_IN_COLLISION if either endpoint collides, else None."""
    start_valid, goal_valid = checker.are_valid(np.stack([start, goal]))
    if not start_valid:
        return PlanStatus.START_IN_COLLISION
    if not goal_valid:
        return PlanStatus.GOAL_IN_COLLISION
    return None
