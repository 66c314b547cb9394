"""Joint-space motion planning over a batched collision-checker interface.

Knows nothing of PyBullet: planners see joint bounds (`ConfigurationSpace`)
and a `CollisionChecker`. Sampling-based planners (`plan_rrt`,
`plan_rrt_connect`, by name in `MOTION_PLANNERS`) return a `PlanningResult`;
smoothing (`shortcut_path`) is its own step; `check_path_densely` re-checks
any path. Trajectory optimisation with Drake is imported on demand from
`trajectory_program` (build) and `trajectory_solver` (solve, reconstruct,
`optimize_trajectory`), so sampling-based planning does not load Drake.
Planning-time geometry models of a described scene: Drake's
(`drake_collision`) and the sphere model (`sphere_checker`, batched checks and
per-pair signed distances; `sphere_screening` puts it in front of an exact
model), imported on demand too.
"""

from kitchen_tamp.motion.collision_checker import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    ValidityMask,
)
from kitchen_tamp.motion.configuration_space import ConfigurationSpace, InvalidMotionQueryError
from kitchen_tamp.motion.joint_path import JointPath, densify_path, path_length, resample_path
from kitchen_tamp.motion.path_verification import PathCheck, check_path_densely
from kitchen_tamp.motion.planners import (
    DEFAULT_MOTION_PLANNER,
    MOTION_PLANNERS,
    MotionPlanner,
    RegisteredPlanner,
    UnknownPlannerError,
    planner_named,
    planner_options,
)
from kitchen_tamp.motion.planning_result import MotionPlanningError, PlanningResult, PlanStatus
from kitchen_tamp.motion.sampling.rrt import RrtHyperparameters, plan_rrt
from kitchen_tamp.motion.sampling.rrt_connect import RrtConnectHyperparameters, plan_rrt_connect
from kitchen_tamp.motion.sampling.shortcut import cut_corners, prune_waypoints, shortcut_path
from kitchen_tamp.motion.sampling.shortcut_settings import ShortcutHyperparameters, SmoothingResult
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker

__all__ = [
    "DEFAULT_MOTION_PLANNER",
    "MOTION_PLANNERS",
    "CollisionChecker",
    "ConfigurationSpace",
    "CountingSegmentChecker",
    "InvalidMotionQueryError",
    "JointConfiguration",
    "JointConfigurations",
    "JointPath",
    "MotionPlanner",
    "MotionPlanningError",
    "PathCheck",
    "PlanStatus",
    "PlanningResult",
    "RegisteredPlanner",
    "RrtConnectHyperparameters",
    "RrtHyperparameters",
    "ShortcutHyperparameters",
    "SmoothingResult",
    "UnknownPlannerError",
    "ValidityMask",
    "check_path_densely",
    "cut_corners",
    "densify_path",
    "path_length",
    "plan_rrt",
    "plan_rrt_connect",
    "planner_named",
    "planner_options",
    "prune_waypoints",
    "resample_path",
    "shortcut_path",
]
