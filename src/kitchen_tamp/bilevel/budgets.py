"""How much a SeSamE run may try: one record, taken by `sesame` and its two smaller forms."""

from __future__ import annotations

from dataclasses import dataclass


def _at_least(name: str, value: float | None, minimum: float) -> None:
    if value is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum:g}, got {value}")


@dataclass(frozen=True)
class SesameBudgets:
    """SeSamE's budgets (``None``: unlimited). The defaults suit cheap samples (toy domains); a
    caller whose every sample costs a motion plan sets smaller ones (the kitchen's are
    ``kitchen_tamp.refinement.KITCHEN_BUDGETS``)."""

    max_plans: int | None = 100
    """Abstract plans to try, best first. A plan dropped at its first failure because a fact
    that failure taught rules it out (``Outcome.PLAN_REFUTED``) does not count: every such plan
    taught something new, so the budget grows with what the task has to teach (one learned
    obstruction for a blocked box, several for a cluttered row) and bounds only the plans that
    failed for reasons the search cannot learn."""
    samples_per_step: int = 10
    """Samples per visit of a step, successes included, before stepping back."""
    max_samples: int | None = None
    """Samples over the whole run."""
    max_samples_per_plan: int | None = None
    """Samples on any one abstract plan before moving to the next."""
    time_budget_s: float | None = 60.0
    """Seconds, checked before every sample."""

    def __post_init__(self) -> None:
        _at_least("max_plans", self.max_plans, 1)
        _at_least("samples_per_step", self.samples_per_step, 1)
        _at_least("max_samples", self.max_samples, 0)
        _at_least("max_samples_per_plan", self.max_samples_per_plan, 0)
        _at_least("time_budget_s", self.time_budget_s, 0)


DEFAULT_BUDGETS = SesameBudgets()
