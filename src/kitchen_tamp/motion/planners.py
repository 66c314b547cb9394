"""Motion planners by name: the one registry the command line's choices and the dispatch read.

Each entry says what a planner is called in reports (its key, e.g. ``rrt_connect``),
the value of ``final_project.py rrt --rrt`` that picks it, and what it does, as
pyperplan's search registry feeds its argparse choices.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Protocol

import numpy.typing as npt

from kitchen_tamp.motion.collision_checker import CollisionChecker
from kitchen_tamp.motion.configuration_space import ConfigurationSpace
from kitchen_tamp.motion.planning_result import PlanningResult
from kitchen_tamp.motion.sampling.rrt import plan_rrt
from kitchen_tamp.motion.sampling.rrt_connect import plan_rrt_connect


class MotionPlanner(Protocol):
    """A planner: its own hyper-parameters if ``hyperparameters`` is None."""

    def __call__(
        self,
        start: npt.ArrayLike,
        goal: npt.ArrayLike,
        space: ConfigurationSpace,
        checker: CollisionChecker,
        hyperparameters: Any = ...,
        *,
        seed: int = ...,
        time_budget_s: float = ...,
    ) -> PlanningResult: ...


@dataclass(frozen=True)
class RegisteredPlanner:
    """A motion planner as the registry knows it."""

    plan: MotionPlanner
    option: str
    """The value of ``final_project.py rrt --rrt`` that picks this planner."""
    summary: str


MOTION_PLANNERS: Mapping[str, RegisteredPlanner] = MappingProxyType({
    "rrt_connect": RegisteredPlanner(plan_rrt_connect, "connect", "RRT-Connect, two trees from both ends"),
    "rrt": RegisteredPlanner(plan_rrt, "basic", "goal-biased RRT, one tree from the start"),
})
"""Planner name (as reports give it) -> planner; the first is the default."""

DEFAULT_MOTION_PLANNER = next(iter(MOTION_PLANNERS))


class UnknownPlannerError(ValueError):
    """A planner name not in `MOTION_PLANNERS`."""


def planner_named(name: str) -> MotionPlanner:
    """The planner registered under `name`, or `UnknownPlannerError` listing the choices."""
    try:
        return MOTION_PLANNERS[name].plan
    except KeyError:
        choices = ", ".join(sorted(MOTION_PLANNERS))
        raise UnknownPlannerError(f"unknown motion planner {name!r}; choose one of {choices}") from None


def planner_options() -> dict[str, str]:
    """The command line's ``--rrt`` values -> planner names, in registry order."""
    return {entry.option: name for name, entry in MOTION_PLANNERS.items()}
