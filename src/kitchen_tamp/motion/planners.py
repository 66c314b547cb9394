"""Motion planners by name, for callers (and CLI choices) that pick one at run time."""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Protocol

import numpy.typing as npt

from kitchen_tamp.motion.collision_checker import CollisionChecker
from kitchen_tamp.motion.configuration_space import ConfigurationSpace
from kitchen_tamp.motion.planning_result import PlanningResult
from kitchen_tamp.motion.sampling.rrt import plan_rrt
from kitchen_tamp.motion.sampling.rrt_connect import plan_rrt_connect


class MotionPlanner(Protocol):
    """A planner called with its default hyper-parameters."""

    def __call__(
        self,
        start: npt.ArrayLike,
        goal: npt.ArrayLike,
        space: ConfigurationSpace,
        checker: CollisionChecker,
        *,
        seed: int = ...,
        time_budget_s: float = ...,
    ) -> PlanningResult: ...


MOTION_PLANNERS: Mapping[str, MotionPlanner] = MappingProxyType(
    {"rrt": plan_rrt, "rrt_connect": plan_rrt_connect}
)
"""Planner name -> planner; the keys are the CLI's choices."""


class UnknownPlannerError(KeyError):
    """A planner name not in `MOTION_PLANNERS`."""

    def __str__(self) -> str:
        return str(self.args[0])


def planner_named(name: str) -> MotionPlanner:
    """The planner registered under `name`, or `UnknownPlannerError` listing the choices."""
    try:
        return MOTION_PLANNERS[name]
    except KeyError:
        choices = ", ".join(sorted(MOTION_PLANNERS))
        raise UnknownPlannerError(f"unknown motion planner {name!r}; choose one of {choices}") from None
