"""Trajectory optimisation with Drake, as build -> solve -> reconstruct.

`build_trajectory_program` (``program``) writes a MathematicalProgram over N
joint waypoints with a clearance constraint; ``solver`` solves it with a
nonlinear solver and reconstructs the path (`optimize_trajectory` does all
three). Importing this package loads Drake.
"""

from kitchen_tamp.motion.trajopt.program import (
    Clearance,
    ClearanceConstraint,
    TrajectoryOptimizationSettings,
    TrajectoryProgram,
    build_trajectory_program,
    initial_waypoints,
    one_at_a_time,
)
from kitchen_tamp.motion.trajopt.solver import (
    NoNonlinearSolverError,
    TrajectoryOptimizationResult,
    nonlinear_solver,
    optimize_trajectory,
    reconstruct_trajectory,
    solve_trajectory_program,
)

__all__ = [
    "Clearance",
    "ClearanceConstraint",
    "NoNonlinearSolverError",
    "TrajectoryOptimizationResult",
    "TrajectoryOptimizationSettings",
    "TrajectoryProgram",
    "build_trajectory_program",
    "initial_waypoints",
    "nonlinear_solver",
    "one_at_a_time",
    "optimize_trajectory",
    "reconstruct_trajectory",
    "solve_trajectory_program",
]
