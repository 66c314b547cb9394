"""Solve and reconstruct steps of trajectory optimisation, and the three steps in one call."""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from pydrake.solvers import (
    IpoptSolver,
    MathematicalProgramResult,
    SnoptSolver,
    SolverInterface,
    SolverOptions,
)

from kitchen_tamp.motion.configuration_space import ConfigurationSpace
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.trajopt.program import Clearance, TrajectoryProgram, build_trajectory_program
from kitchen_tamp.motion.trajopt.settings import TrajectoryOptimizationSettings


class NoNonlinearSolverError(Exception):
    """Neither SNOPT nor IPOPT is available in this Drake build."""


@functools.cache
def nonlinear_solver() -> SolverInterface:
    """SNOPT if this Drake has it, else IPOPT; chosen once per process."""
    for solver in (SnoptSolver(), IpoptSolver()):
        if solver.available() and solver.enabled():
            return solver
    raise NoNonlinearSolverError("Drake has neither SNOPT nor IPOPT available")


def _solver_options(solver: SolverInterface, settings: TrajectoryOptimizationSettings) -> SolverOptions:
    """Iteration limit and tolerances of ``settings`` in the solver's own option names."""
    options = SolverOptions()
    snopt = solver.solver_id() == SnoptSolver.id()
    names = (
        ("Major iterations limit", "Major optimality tolerance", "Major feasibility tolerance")
        if snopt
        else ("max_iter", "tol", "constr_viol_tol")
    )
    values = (settings.max_iterations, settings.optimality_tolerance, settings.feasibility_tolerance)
    for name, value in zip(names, values, strict=True):
        if value is not None:
            options.SetOption(solver.solver_id(), name, value)
    return options


@dataclass(frozen=True, eq=False)
class TrajectoryOptimizationResult:
    """Optimised waypoints (N, d) and how the solver got there.

    `iterations` is None when the solver does not report it (Drake exposes
    neither SNOPT's nor IPOPT's count); `collision_evaluations` counts the
    configurations whose clearance the solver asked for instead.
    """

    success: bool
    waypoints: JointPath
    solver_name: str
    solution_status: str
    iterations: int | None
    cost: float
    solve_time_s: float
    collision_evaluations: int


def solve_trajectory_program(
    problem: TrajectoryProgram, solver: SolverInterface | None = None
) -> MathematicalProgramResult:
    """Run the solver (default `nonlinear_solver()`) from the program's initial guess."""
    solver = solver or nonlinear_solver()
    options = _solver_options(solver, problem.settings)
    return solver.Solve(problem.program, None, options)


def reconstruct_trajectory(
    problem: TrajectoryProgram, result: MathematicalProgramResult, solve_time_s: float
) -> TrajectoryOptimizationResult:
    """Read the waypoints and solver record out of a Drake result."""
    waypoints: npt.NDArray[np.float64] = np.asarray(result.GetSolution(problem.waypoints), dtype=np.float64)
    return TrajectoryOptimizationResult(
        success=bool(result.is_success()),
        waypoints=waypoints,
        solver_name=result.get_solver_id().name(),
        solution_status=result.get_solution_result().name,
        iterations=None,
        cost=float(result.get_optimal_cost()),
        solve_time_s=solve_time_s,
        collision_evaluations=problem.collision_evaluations,
    )


def optimize_trajectory(
    start: npt.ArrayLike,
    goal: npt.ArrayLike,
    space: ConfigurationSpace,
    clearance: Clearance,
    settings: TrajectoryOptimizationSettings | None = None,
    initial_path: JointPath | None = None,
) -> TrajectoryOptimizationResult:
    """Build, solve and reconstruct. A start or goal in collision (negative clearance) fails
    unsolved."""
    settings = settings or TrajectoryOptimizationSettings()
    problem = build_trajectory_program(start, goal, space, clearance, settings, initial_path)
    ends, _ = clearance(problem.initial_guess[[0, -1]])
    for name, value in zip(("start", "goal"), ends, strict=True):
        if value < 0.0:
            return TrajectoryOptimizationResult(
                success=False,
                waypoints=problem.initial_guess,
                solver_name=nonlinear_solver().solver_id().name(),
                solution_status=f"{name} in collision",
                iterations=None,
                cost=float("nan"),
                solve_time_s=0.0,
                collision_evaluations=problem.collision_evaluations,
            )
    clock_start = time.perf_counter()
    result = solve_trajectory_program(problem)
    return reconstruct_trajectory(problem, result, time.perf_counter() - clock_start)
