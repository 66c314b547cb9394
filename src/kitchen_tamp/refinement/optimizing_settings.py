"""The settings ``optimizes`` runs trajectory optimisation with (`DEFAULT_SETTINGS`), apart from
the back end that uses them: the command line reads them without loading Drake."""

from __future__ import annotations

from kitchen_tamp.motion.trajopt.settings import TrajectoryOptimizationSettings

DEFAULT_SETTINGS = TrajectoryOptimizationSettings(
    num_waypoints=20,
    max_step=0.25,
    collision_margin=0.005,
    max_iterations=200,
    optimality_tolerance=1e-2,
    feasibility_tolerance=1e-5,
    samples_between_waypoints=4,
)
"""20 waypoints (more when a joint must travel further than 0.25 rad a step), and 5 mm of clearance
at every waypoint and at four points between each two: the collision points are as dense as with
the original project's 50 waypoints and one midpoint. SNOPT's time grows much faster than the
waypoint count (its quasi-Newton Hessian learns the path's curvature one waypoint joint at a
time), and an optimality tolerance of 1e-2 (SNOPT's default is 1e-6) stops it once the path is
within a fraction of a percent of its best length: on the hard moves of problem.pddl and
problem_hard.pddl (seed 0), 0.11-0.15 CPU s per move instead of 0.3-3.3 s with 50 waypoints
and 1e-3, with paths 0.1-0.9% longer. At most 200 major iterations."""
