"""What a trajectory program is asked for (`TrajectoryOptimizationSettings`), apart from Drake:
a run that never optimises reads these (the command line's defaults) without loading Drake."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class TrajectoryOptimizationSettings:
    """Shape and constraints of the program (radians, and the signed distance's units)."""

    num_waypoints: int = 50
    max_step: float = 0.1
    collision_margin: float = 0.01
    max_iterations: int = 1000
    optimality_tolerance: float | None = None
    """Solver's optimality tolerance (SNOPT "Major optimality tolerance", IPOPT "tol");
    None keeps the solver's default."""
    feasibility_tolerance: float | None = None
    """SNOPT's "Major feasibility tolerance" (IPOPT "constr_viol_tol"); None keeps the default."""
    samples_between_waypoints: int = 1
    """Extra collision constraints on each step, at evenly spaced points between two waypoints:
    the straight segment between waypoints is what gets executed and verified."""
    waypoints_per_constraint: int = 10
    """Steps whose collision points one constraint (one batched clearance call) covers."""

    def __post_init__(self) -> None:
        if self.num_waypoints < 2:
            raise ValueError(f"num_waypoints must be at least 2, got {self.num_waypoints}")
        if self.max_step <= 0.0:
            raise ValueError(f"max_step must be positive, got {self.max_step}")
        if self.max_iterations < 1:
            raise ValueError(f"max_iterations must be at least 1, got {self.max_iterations}")
        if self.samples_between_waypoints < 0:
            raise ValueError(f"samples_between_waypoints must be >= 0, got {self.samples_between_waypoints}")
        if self.waypoints_per_constraint < 1:
            raise ValueError(f"waypoints_per_constraint must be >= 1, got {self.waypoints_per_constraint}")
