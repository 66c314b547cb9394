"""Turning a symbolic plan into arm motion in the kitchen, as SeSamE: skills give targets,
a motion back end (sampling-based planning, or trajectory optimisation) connects them,
and the bilevel planner backtracks when a step cannot be refined."""

from kitchen_tamp.refinement.kitchen_sesame import KITCHEN_BUDGETS, SesameRefinement, refine_with_sesame
from kitchen_tamp.refinement.motion_backend import (
    MotionBackend,
    MotionSolution,
    SamplingMotionBackend,
)
from kitchen_tamp.refinement.refine_action import ActionSampleRecord, RefinedKitchenPlan, refine_action

__all__ = [
    "KITCHEN_BUDGETS",
    "ActionSampleRecord",
    "MotionBackend",
    "MotionSolution",
    "RefinedKitchenPlan",
    "SamplingMotionBackend",
    "SesameRefinement",
    "refine_action",
    "refine_with_sesame",
]
