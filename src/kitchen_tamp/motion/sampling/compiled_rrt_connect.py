"""RRT-Connect's loop in compiled calls (`rrt_connect_kernel`), driven from Python between them.

Each call runs the iterations of one block of samples (or fewer, when the trees need room);
between calls the clock is read and the tree arrays grown, so the time budget is kept to within
one block of iterations. Used by `plan_rrt_connect` when the checker is the sphere model
(`CompiledValidity`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from kitchen_tamp.motion.collision_checker import JointConfiguration
from kitchen_tamp.motion.configuration_space import UniformSamples
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.planning_result import PlanningResult, PlanStatus
from kitchen_tamp.motion.sampling.configuration_tree import NO_PARENT
from kitchen_tamp.motion.sampling.rrt_connect_kernel import (
    COUNTER_CHECKS,
    COUNTER_COUNT,
    COUNTER_ITERATIONS,
    COUNTER_JOINED,
    COUNTER_SIZES,
    ENDS_JOINED,
    GOAL_COLLIDES,
    START_COLLIDES,
    ends_and_line_checked,
    joined_path,
    rrt_connect_iterations,
)

_ITERATIONS: Any = rrt_connect_iterations
"""The compiled kernel, untyped for mypy (numba's dispatcher stubs take no argument list)."""
_ENDS_AND_LINE: Any = ends_and_line_checked
_JOINED_PATH: Any = joined_path

INITIAL_CAPACITY = 1024
"""Rows of each tree's arrays at first; they double when a block of iterations might not fit."""


@dataclass(frozen=True)
class LoopSettings:
    """What the loop is given: step and resolution (rad), its limits and its clock."""

    step_size: float
    resolution: float
    max_iterations: int
    tree_balance: float
    deadline: float
    clock: Callable[[], float]


@dataclass(frozen=True, eq=False)
class LoopOutcome:
    """How the loop ended (SOLVED with a path, or the limit it hit) and its counts."""

    status: PlanStatus
    path: JointPath | None
    iterations: int
    nodes: int
    collision_checks: int

    def result(self, checked_before: int, planning_time_s: float) -> PlanningResult:
        """The planner's answer, counting ``checked_before`` configurations checked before the loop."""
        return PlanningResult(
            status=self.status,
            path=self.path,
            iterations=self.iterations,
            nodes=self.nodes,
            collision_checks=checked_before + self.collision_checks,
            planning_time_s=planning_time_s,
        )


class _Trees:
    """Both trees' arrays, as the kernel takes them: tree 0 rooted at the start, 1 at the goal."""

    def __init__(self, start: JointConfiguration, goal: JointConfiguration) -> None:
        self.nodes = np.empty((2, INITIAL_CAPACITY, start.size))
        self.parents = np.empty((2, INITIAL_CAPACITY), dtype=np.int64)
        self.squared_norms = np.empty((2, INITIAL_CAPACITY))
        self.counters = np.zeros(COUNTER_COUNT, dtype=np.int64)
        for tree, root in enumerate((start, goal)):
            self.nodes[tree, 0] = root
            self.parents[tree, 0] = NO_PARENT
            self.squared_norms[tree, 0] = float(root @ root)
            self.counters[COUNTER_SIZES + tree] = 1

    @property
    def node_count(self) -> int:
        return int(self.counters[COUNTER_SIZES] + self.counters[COUNTER_SIZES + 1])

    def grow(self) -> None:
        """Double the rows of every tree array."""
        capacity = self.nodes.shape[1]
        nodes = np.empty((2, 2 * capacity, self.nodes.shape[2]))
        parents = np.empty((2, 2 * capacity), dtype=np.int64)
        squared_norms = np.empty((2, 2 * capacity))
        nodes[:, :capacity], parents[:, :capacity] = self.nodes, self.parents
        squared_norms[:, :capacity] = self.squared_norms
        self.nodes, self.parents, self.squared_norms = nodes, parents, squared_norms

    def joined_path(self) -> JointPath:
        """Start-tree branch to its end node, then the goal-tree branch backwards (shared node once)."""
        path: JointPath = _JOINED_PATH(self.nodes, self.parents, self.counters)
        return path


def run_compiled_loop(
    start: JointConfiguration,
    goal: JointConfiguration,
    samples: UniformSamples,
    compiled: tuple[Any, float],
    settings: LoopSettings,
    checked_before: int = 0,
) -> LoopOutcome:
    """RRT-Connect's iterations from the two roots until the trees join or a limit is hit;
    ``compiled`` is the sphere model's (`ValidityArrays`, margin); the outcome's checks count
    ``checked_before`` too."""
    arrays, margin = compiled
    trees = _Trees(start, goal)
    counters = trees.counters
    resolutions_per_step = max(1, round(settings.step_size / settings.resolution))
    reach = samples.space.diagonal
    room = 2 + math.ceil(reach / (resolutions_per_step * settings.resolution))
    status = PlanStatus.ITERATION_LIMIT
    while counters[COUNTER_ITERATIONS] < settings.max_iterations:
        if settings.clock() >= settings.deadline:
            status = PlanStatus.TIME_LIMIT
            break
        if max(counters[COUNTER_SIZES], counters[COUNTER_SIZES + 1]) + room > trees.nodes.shape[1]:
            trees.grow()
        block = samples.upcoming()
        used = _ITERATIONS(
            block,
            settings.step_size,
            settings.resolution,
            settings.max_iterations,
            room,
            trees.nodes,
            trees.parents,
            trees.squared_norms,
            counters,
            arrays,
            margin,
            settings.tree_balance,
        )
        samples.skip(int(used))
        if counters[COUNTER_JOINED]:
            status = PlanStatus.SOLVED
            break
    path = trees.joined_path() if status is PlanStatus.SOLVED else None
    iterations, checks = int(counters[COUNTER_ITERATIONS]), checked_before + int(counters[COUNTER_CHECKS])
    return LoopOutcome(status, path, iterations, trees.node_count, checks)


def plan_compiled(
    start: JointConfiguration,
    goal: JointConfiguration,
    samples: UniformSamples,
    compiled: tuple[Any, float],
    settings: LoopSettings,
) -> LoopOutcome:
    """`plan_rrt_connect` with the sphere model's compiled validity ``compiled``: the ends checked
    (START_ or GOAL_IN_COLLISION), then the straight line between them (SOLVED with the two
    ends), then `run_compiled_loop`; the same checks, counted alike, as through a
    `CountingSegmentChecker` of the checker, without its Python layers."""
    arrays, margin = compiled
    found, checked = _ENDS_AND_LINE(start, goal, settings.resolution, arrays, margin)
    if found in (START_COLLIDES, GOAL_COLLIDES):
        status = PlanStatus.START_IN_COLLISION if found == START_COLLIDES else PlanStatus.GOAL_IN_COLLISION
        return LoopOutcome(status, None, 0, 2, int(checked))
    if found == ENDS_JOINED:
        return LoopOutcome(PlanStatus.SOLVED, np.stack([start, goal]), 0, 2, int(checked))
    return run_compiled_loop(start, goal, samples, compiled, settings, int(checked))
