"""Sampling-based motion planning: RRT, RRT-Connect, their configuration trees, and shortcutting.

Planners take joint bounds (`ConfigurationSpace`), a `CollisionChecker`, a seed
and a time budget, and return a `PlanningResult`; smoothing (`shortcut_path`)
is its own step, as OMPL's ``simplifySolution`` is.
"""

from kitchen_tamp.motion.sampling.configuration_tree import ConfigurationTree
from kitchen_tamp.motion.sampling.rrt import RrtHyperparameters, plan_rrt, steer
from kitchen_tamp.motion.sampling.rrt_connect import RrtConnectHyperparameters, plan_rrt_connect
from kitchen_tamp.motion.sampling.shortcut import (
    connect_furthest_vertices,
    cut_corners,
    prune_waypoints,
    shortcut_path,
)
from kitchen_tamp.motion.sampling.shortcut_settings import ShortcutHyperparameters, SmoothingResult

__all__ = [
    "ConfigurationTree",
    "RrtConnectHyperparameters",
    "RrtHyperparameters",
    "ShortcutHyperparameters",
    "SmoothingResult",
    "connect_furthest_vertices",
    "cut_corners",
    "plan_rrt",
    "plan_rrt_connect",
    "prune_waypoints",
    "shortcut_path",
    "steer",
]
