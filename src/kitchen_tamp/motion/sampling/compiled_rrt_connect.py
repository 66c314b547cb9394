"""RRT-Connect's loop in compiled calls (`rrt_connect_kernel`), driven from Python between them.

The first call checks the ends and the straight line, makes the trees and runs the first block of
iterations; most queries end in it, so a query is one compiled call. Between further calls, each
running one block of iterations, the clock is read and the tree arrays grown, so the time budget
is kept to within one block of iterations. Used by `plan_rrt_connect` when the checker is the
sphere model (`CompiledValidity`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from kitchen_tamp.motion.collision_checker import JointConfiguration
from kitchen_tamp.motion.configuration_space import ConfigurationSpace
from kitchen_tamp.motion.joint_path import JointPath
from kitchen_tamp.motion.planning_result import PlanningResult, PlanStatus
from kitchen_tamp.motion.sampling.rrt_connect_kernel import (
    COUNTER_CHECKS,
    COUNTER_ITERATIONS,
    COUNTER_JOINED,
    COUNTER_ROOM,
    COUNTER_SIZES,
    ENDS_JOINED,
    GOAL_COLLIDES,
    START_COLLIDES,
    first_block,
    joined_path,
    rrt_connect_iterations,
)

if TYPE_CHECKING:
    from kitchen_tamp.motion.sampling.rrt_connect import RrtConnectHyperparameters

_FIRST_BLOCK: Any = first_block
"""The compiled kernels, untyped for mypy (numba's dispatcher stubs take no argument list)."""
_ITERATIONS: Any = rrt_connect_iterations
_JOINED_PATH: Any = joined_path

INITIAL_CAPACITY = 1024
"""Rows of each tree's arrays at first; they double when a block of iterations might not fit."""
BLOCK = 64
"""Iterations a compiled call runs at most: the clock is read between calls."""


@dataclass(frozen=True)
class LoopQuery:
    """What the loop searches: the samples' box and seed (`counter_samples`), the search's
    hyperparameters, and the clock's deadline."""

    space: ConfigurationSpace
    seed: int
    search: RrtConnectHyperparameters
    deadline: float


@dataclass(frozen=True, eq=False)
class LoopOutcome:
    """How the loop ended (SOLVED with a path, or the limit it hit) and its counts."""

    status: PlanStatus
    path: JointPath | None
    iterations: int
    nodes: int
    collision_checks: int

    def result(self, planning_time_s: float) -> PlanningResult:
        """The planner's answer."""
        return PlanningResult(
            status=self.status,
            path=self.path,
            iterations=self.iterations,
            nodes=self.nodes,
            collision_checks=self.collision_checks,
            planning_time_s=planning_time_s,
        )


class _Trees:
    """Both trees' arrays, as the kernel takes them: tree 0 rooted at the start, 1 at the goal."""

    def __init__(self, nodes: Any, parents: Any, squared_norms: Any, counters: Any) -> None:
        self.nodes, self.parents, self.squared_norms, self.counters = nodes, parents, squared_norms, counters

    def may_lack_room(self) -> bool:
        """Whether a tree may have fewer free rows than an iteration may add."""
        counters = self.counters
        largest = max(counters[COUNTER_SIZES], counters[COUNTER_SIZES + 1])
        return bool(largest + counters[COUNTER_ROOM] > self.nodes.shape[1])

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


def _further_blocks(trees: _Trees, compiled: tuple[Any, float], query: LoopQuery) -> PlanStatus:
    """Blocks of iterations after the first, until the trees are joined (SOLVED) or a limit is hit."""
    arrays, margin = compiled
    search, counters = query.search, trees.counters
    while counters[COUNTER_ITERATIONS] < search.max_iterations:
        if search.clock() >= query.deadline:
            return PlanStatus.TIME_LIMIT
        if trees.may_lack_room():
            trees.grow()
        _ITERATIONS(
            query.seed,
            query.space.lower,
            query.space.upper,
            BLOCK,
            search.step_size,
            search.edge_resolution,
            search.max_iterations,
            trees.nodes,
            trees.parents,
            trees.squared_norms,
            counters,
            arrays,
            margin,
            search.tree_balance,
        )
        if counters[COUNTER_JOINED]:
            return PlanStatus.SOLVED
    return PlanStatus.ITERATION_LIMIT


def _first_call(
    start: JointConfiguration, goal: JointConfiguration, compiled: tuple[Any, float], query: LoopQuery
) -> tuple[Any, ...]:
    """`rrt_connect_kernel.first_block` on the query: its ends, line, first block of iterations."""
    arrays, margin = compiled
    search = query.search
    first: tuple[Any, ...] = _FIRST_BLOCK(
        start,
        goal,
        query.seed,
        query.space.lower,
        query.space.upper,
        BLOCK,
        search.step_size,
        search.edge_resolution,
        search.max_iterations,
        INITIAL_CAPACITY,
        arrays,
        margin,
        search.tree_balance,
    )
    return first


def compile_loop_kernels(home: JointConfiguration, compiled: tuple[Any, float], query: LoopQuery) -> None:
    """Run each compiled call of the loop once, so that numba's cache holds them
    (`kitchen_tamp.cli.prepare`): the first call from ``home`` to itself, then a block of one
    iteration on its trees and the path through them."""
    trees = _Trees(*_first_call(home, home, compiled, query)[3:])
    _further_blocks(trees, compiled, replace(query, search=replace(query.search, max_iterations=1)))
    trees.joined_path()


def plan_compiled(
    start: JointConfiguration, goal: JointConfiguration, compiled: tuple[Any, float], query: LoopQuery
) -> LoopOutcome:
    """`plan_rrt_connect` with the sphere model's compiled validity ``compiled`` (its
    `ValidityArrays` and margin): the ends checked (START_ or GOAL_IN_COLLISION), then the straight
    line between them (SOLVED with the two ends), then RRT-Connect's iterations until the trees join
    or a limit is hit; the same checks, counted alike, as through a `CountingSegmentChecker` of the
    checker, without its Python layers."""
    found, checked, path, *tree_arrays = _first_call(start, goal, compiled, query)
    if found in (START_COLLIDES, GOAL_COLLIDES):
        status = PlanStatus.START_IN_COLLISION if found == START_COLLIDES else PlanStatus.GOAL_IN_COLLISION
        return LoopOutcome(status, None, 0, 2, int(checked))
    if found == ENDS_JOINED:
        return LoopOutcome(PlanStatus.SOLVED, path, 0, 2, int(checked))
    trees = _Trees(*tree_arrays)
    counters = trees.counters
    status = PlanStatus.SOLVED if counters[COUNTER_JOINED] else _further_blocks(trees, compiled, query)
    if status is PlanStatus.SOLVED and not path.shape[0]:
        path = trees.joined_path()
    iterations, checks = int(counters[COUNTER_ITERATIONS]), int(checked) + int(counters[COUNTER_CHECKS])
    found_path = path if status is PlanStatus.SOLVED else None
    return LoopOutcome(status, found_path, iterations, trees.node_count, checks)
