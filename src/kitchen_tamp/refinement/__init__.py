"""Turning a symbolic plan into arm motion in the kitchen: skills give targets, a motion
back end (sampling-based planning, or trajectory optimisation) connects them."""

from kitchen_tamp.refinement.motion_backend import (
    VERIFICATION_RESOLUTION,
    MotionBackend,
    MotionSolution,
    SamplingMotionBackend,
)
from kitchen_tamp.refinement.refine_plan import (
    DEFAULT_SAMPLES_PER_STEP,
    RefinedPlan,
    RefinementFailure,
    StepRecord,
    refine_action,
    refine_plan,
)

__all__ = [
    "DEFAULT_SAMPLES_PER_STEP",
    "VERIFICATION_RESOLUTION",
    "MotionBackend",
    "MotionSolution",
    "RefinedPlan",
    "RefinementFailure",
    "SamplingMotionBackend",
    "StepRecord",
    "refine_action",
    "refine_plan",
]
