"""Bilevel planning: plan abstractly, refine each abstract step by sampling, backtrack when geometry says no.

Generic over low-level states x, actions u, abstract states s and abstract
actions a; knows nothing of PyBullet or the kitchen. Typical use::

    problem = BilevelProblem(initial_state=x0, abstraction=Abstraction(psi, successors, is_goal),
                             sampler_for=lambda a: samplers[a.name])
    result = sesame(problem, SesameBudgets(samples_per_step=10, max_samples=500), seed=0)
    if result.solved:
        for step in result.plan.steps: ...

Planners: :func:`abstract_bfs`, :func:`sesame` and, as SeSamE with smaller
budgets, :func:`backtracking_refinement` (one abstract plan) and
:func:`greedy_refinement` (one plan, one sample per step). Relational
abstractions from a PDDL task: :mod:`kitchen_tamp.bilevel.relational`; failures
that teach the abstract search (obstructions, places out of reach):
:mod:`kitchen_tamp.bilevel.feedback`. A toy domain: :mod:`kitchen_tamp.bilevel.toy_rooms`.
"""

from kitchen_tamp.bilevel.abstract_bfs import abstract_bfs
from kitchen_tamp.bilevel.abstract_plans import shortest_first_plans
from kitchen_tamp.bilevel.abstraction import (
    Abstraction,
    AbstractPlan,
    AbstractPlanGenerator,
    AbstractTransition,
)
from kitchen_tamp.bilevel.budgets import SesameBudgets
from kitchen_tamp.bilevel.feedback import (
    LearningPlanGenerator,
    Obstruction,
    Unreachable,
    fact_text,
)
from kitchen_tamp.bilevel.planning_graph import (
    AbstractActionEdge,
    AbstractorEdge,
    ActionEdge,
    FailedSample,
    PlanningGraph,
    StateNode,
)
from kitchen_tamp.bilevel.problem import BilevelProblem, SamplingFailure, TrajectorySampler
from kitchen_tamp.bilevel.relational import (
    relational_abstraction,
    relational_plan_generator,
    relational_problem,
    samplers_by_operator,
)
from kitchen_tamp.bilevel.replay import plan_reaches_goal, replay_refined_plan
from kitchen_tamp.bilevel.results import (
    BilevelResult,
    Outcome,
    PlanAttempt,
    PlanningCounts,
    RefinedPlan,
    RefinedStep,
    SampleEvent,
    StepSamplingRecord,
)
from kitchen_tamp.bilevel.sampling_session import SampleCallback
from kitchen_tamp.bilevel.sesame import backtracking_refinement, greedy_refinement, sesame
from kitchen_tamp.bilevel.trajectory import Trajectory, concatenate, rollout

__all__ = [
    "AbstractActionEdge",
    "AbstractPlan",
    "AbstractPlanGenerator",
    "AbstractTransition",
    "Abstraction",
    "AbstractorEdge",
    "ActionEdge",
    "BilevelProblem",
    "BilevelResult",
    "FailedSample",
    "LearningPlanGenerator",
    "Obstruction",
    "Outcome",
    "PlanAttempt",
    "PlanningCounts",
    "PlanningGraph",
    "RefinedPlan",
    "RefinedStep",
    "SampleCallback",
    "SampleEvent",
    "SamplingFailure",
    "SesameBudgets",
    "StateNode",
    "StepSamplingRecord",
    "Trajectory",
    "TrajectorySampler",
    "Unreachable",
    "abstract_bfs",
    "backtracking_refinement",
    "concatenate",
    "fact_text",
    "greedy_refinement",
    "plan_reaches_goal",
    "relational_abstraction",
    "relational_plan_generator",
    "relational_problem",
    "replay_refined_plan",
    "rollout",
    "samplers_by_operator",
    "sesame",
    "shortest_first_plans",
]
