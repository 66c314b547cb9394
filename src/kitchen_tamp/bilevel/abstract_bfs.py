"""Abstract breadth-first search: grow the planning graph one abstract state at a time.

Abstract states are expanded in breadth-first order from Psi(x_0). Expanding
``s`` takes each abstract transition ``(s, a, s')`` in the order the successor
function gives them and draws up to ``samples_per_transition`` samples for it,
taking the state nodes already in the graph at ``s`` in turn as the start of
each sample. Every successful sample adds a state node at ``s'``; the first
time ``s'`` gets one it joins the queue. Transitions into abstract states
already expanded are skipped: new nodes there would never be used. The search
stops at the first state node whose abstract state is a goal; the plan is the
path of action edges that reached it.

Unlike SeSamE it needs no abstract plan and never backtracks, and since every
abstract state can hold several low-level states, a bad sample is not fatal as
long as another sample into the same abstract state was better. The price is
breadth: it samples every transition near the start, useful or not.
"""

from __future__ import annotations

from collections import deque
from typing import TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstraction import AbstractTransition
from kitchen_tamp.bilevel.problem import BilevelProblem
from kitchen_tamp.bilevel.results import BilevelResult, Outcome, PlanningCounts
from kitchen_tamp.bilevel.sampling_session import Budget, SampleCallback, SamplingSession

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")

DEFAULT_SAMPLES_PER_TRANSITION = 3


def abstract_bfs(
    problem: BilevelProblem[X, U, S, A],
    *,
    seed: int = 0,
    samples_per_transition: int = DEFAULT_SAMPLES_PER_TRANSITION,
    max_samples: int | None = None,
    time_budget_s: float | None = 60.0,
    on_sample: SampleCallback[S, A] | None = None,
) -> BilevelResult[X, U, S, A]:
    """Breadth-first over abstract states, ``samples_per_transition`` samples per abstract transition.

    Budgets (``None``: unlimited): ``max_samples`` in all, ``time_budget_s``
    seconds (checked before every sample).
    """
    if samples_per_transition < 1:
        raise ValueError(f"samples_per_transition must be >= 1, got {samples_per_transition}")
    session = SamplingSession(problem, np.random.default_rng(seed), Budget(max_samples, time_budget_s),
                              on_sample)
    abstraction = problem.abstraction
    graph = session.graph

    def result(outcome: Outcome, detail: str, node: int | None = None) -> BilevelResult[X, U, S, A]:
        counts = PlanningCounts(session.samples, session.failures, backtracks=0, abstract_plans=0)
        plan = None if node is None else session.refined_plan(node)
        return BilevelResult("abstract_bfs", plan, graph, counts, (), outcome, detail, session.elapsed())

    initial = graph.abstract_state_of(session.root)
    if abstraction.is_goal(initial):
        return result(Outcome.SOLVED, "the initial state is a goal", session.root)
    queued = {initial}
    expanded: set[S] = set()
    frontier = deque([initial])
    while frontier:
        source = frontier.popleft()
        expanded.add(source)
        starts = graph.nodes_in(source)
        for action, target in abstraction.successors(source):
            if target in expanded:
                continue
            transition = AbstractTransition(source, action, target)
            for attempt in range(samples_per_transition):
                spent = session.budget_spent()
                if spent is not None:
                    return result(spent, f"{spent.value} with {len(expanded)} abstract states expanded")
                node = session.draw(starts[attempt % len(starts)], transition)
                if node is None:
                    continue
                if abstraction.is_goal(target):
                    return result(Outcome.SOLVED, f"goal reached after {len(expanded)} abstract states", node)
                if target not in queued:
                    queued.add(target)
                    frontier.append(target)
    exhausted = Outcome.GRAPH_EXHAUSTED
    return result(exhausted, f"{exhausted.value}: {len(expanded)} abstract states expanded, no goal reached")
