"""SeSamE (search, then sample): abstract plans shortest first, each refined with backtracking.

The one loop behind three planners:

* :func:`sesame` — abstract plans from the problem's plan generator, best first,
  each refined with backtracking, until one is refined or a budget (plans,
  samples, time) runs out;
* :func:`backtracking_refinement` — SeSamE with ``max_plans=1``: one abstract
  plan, up to ``samples_per_step`` samples per step before stepping back;
* :func:`greedy_refinement` — SeSamE with ``max_plans=1, samples_per_step=1``:
  one sample per step, so the first failure ends the run.

Backtracking: step ``i`` is sampled from the state the previous step reached.
A success moves on to step ``i + 1``; a step that has been sampled
``samples_per_step`` times since it was last entered, successes included, gives
up and step ``i - 1`` is sampled again (one backtrack), with its own count
carrying on. When the first step gives up, the abstract plan is abandoned and
the next one is tried.

Why tries and not failures: a sample that succeeded but whose later steps all
gave up has failed too, only further down. Counting failures alone would let a
step whose samples always succeed resample forever in front of a dead end (with
``samples_per_step=1``, greedy refinement would not even stop at its first
failure), and SeSamE would reach its next abstract plan only through a sample
budget. Counting tries
bounds one plan of ``n`` steps at ``K + K**2 + ... + K**n`` samples for
``K = samples_per_step``, as in the original SeSamE (Silver et al., "Learning
Symbolic Operators for Task and Motion Planning", 2021), whose low-level search
also counts every try of a step.

Failure feedback (``kitchen_tamp.bilevel.feedback``): when the plan generator
learns (``LearningPlanGenerator``), every failed sample's ``feedback`` is handed
to it. If it learned something new that rules the current plan out, the plan is
dropped at once (``Outcome.PLAN_REFUTED``) rather than backtracked over, and the
following plans come from a fresh enumeration over what it knows now, skipping
plans already tried. Such a dropped plan does not count against the plan budget: it
taught the search a new fact, and the facts there are to learn are finite, so the
search keeps enumerating while failures still teach it something (the sample and time
budgets still bound the run).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Generic, TypeVar

import numpy as np

from kitchen_tamp.bilevel.abstract_plans import shortest_first_plans
from kitchen_tamp.bilevel.abstraction import AbstractPlan, AbstractPlanGenerator
from kitchen_tamp.bilevel.budgets import DEFAULT_BUDGETS, SesameBudgets
from kitchen_tamp.bilevel.feedback import LearningPlanGenerator, fact_text
from kitchen_tamp.bilevel.problem import BilevelProblem
from kitchen_tamp.bilevel.results import (
    BilevelResult,
    Outcome,
    PlanAttempt,
    PlanningCounts,
    StepSamplingRecord,
)
from kitchen_tamp.bilevel.sampling_session import Budget, SampleCallback, SamplingSession

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")


@dataclass
class _StepCounter(Generic[A]):
    action: A
    samples: int = 0
    failures: int = 0
    backtracks: int = 0
    last_failure: str | None = None

    def record(self, plan_index: int, index: int) -> StepSamplingRecord[A]:
        return StepSamplingRecord(
            plan_index, index, self.action, self.samples, self.failures, self.backtracks, self.last_failure
        )


def plan_generator_of(problem: BilevelProblem[X, U, S, A]) -> AbstractPlanGenerator[S, A]:
    """The problem's own plan generator, else shortest-first over its abstract successor function."""
    if problem.plan_generator is not None:
        return problem.plan_generator
    return shortest_first_plans(problem.abstraction.successors, problem.abstraction.is_goal)


@dataclass
class _Learning(Generic[S, A]):
    """What the failures taught the plan generator (nothing, if it does not learn)."""

    generator: AbstractPlanGenerator[S, A]
    facts: list[object]

    def refutes(self, session: SamplingSession[X, U, S, A], plan: AbstractPlan[S, A]) -> str | None:
        """Feed the last failed sample's facts to the generator; the new fact that rules ``plan``
        out, in words, or None."""
        generator = self.generator
        feedback = session.graph.failed_samples[-1].error.feedback
        if not feedback or not isinstance(generator, LearningPlanGenerator):
            return None
        new = generator.learn(feedback)
        self.facts.extend(new)
        if new and not generator.admits(plan):
            return "; ".join(fact_text(fact) for fact in new)
        return None


def _refine_with_backtracking(
    session: SamplingSession[X, U, S, A],
    abstract_plan: AbstractPlan[S, A],
    plan_index: int,
    budgets: SesameBudgets,
    learning: _Learning[S, A],
) -> tuple[PlanAttempt[S, A], int | None]:
    """Refine one abstract plan: the attempt's record and the final state node (``None`` on failure)."""
    samples_per_step, max_samples_per_plan = budgets.samples_per_step, budgets.max_samples_per_plan
    transitions = abstract_plan.transitions
    counters = [_StepCounter(t.action) for t in transitions]
    nodes = [session.root] * (len(transitions) + 1)
    tries_since_entered = [0] * len(transitions)
    plan_samples = 0
    deepest = 0
    step = 0

    def attempt(outcome: Outcome, detail: str) -> PlanAttempt[S, A]:
        steps = tuple(counter.record(plan_index, i) for i, counter in enumerate(counters))
        return PlanAttempt(plan_index, abstract_plan, steps, outcome, detail)

    def blocked_at() -> str:
        counter = counters[deepest]
        return (f"refined {deepest} of {len(transitions)} steps at best; step {deepest + 1} "
                f"({counter.action}) last failed: {counter.last_failure}")

    while step < len(transitions):
        # Every draw counts against the step, a success too: see the module docstring.
        if tries_since_entered[step] >= samples_per_step:
            tries_since_entered[step] = 0
            step -= 1
            if step < 0:
                return attempt(Outcome.STEPS_EXHAUSTED, blocked_at()), None
            if tries_since_entered[step] < samples_per_step:
                counters[step].backtracks += 1
            continue
        spent = session.budget_spent()
        if spent is None and max_samples_per_plan is not None and plan_samples >= max_samples_per_plan:
            spent = Outcome.PLAN_SAMPLE_BUDGET
        if spent is not None:
            return attempt(spent, f"{spent.value}; {blocked_at()}"), None
        tries_since_entered[step] += 1
        plan_samples += 1
        counters[step].samples += 1
        node = session.draw(nodes[step], transitions[step], plan_index, step)
        if node is None:
            counters[step].failures += 1
            counters[step].last_failure = session.graph.failed_samples[-1].message
            refuted = learning.refutes(session, abstract_plan)
            if refuted is not None:
                return attempt(Outcome.PLAN_REFUTED, f"step {step + 1} ({counters[step].action}): "
                                                     f"{refuted}"), None
            continue
        step += 1
        nodes[step] = node
        deepest = max(deepest, min(step, len(transitions) - 1))
    return attempt(Outcome.SOLVED, f"refined in {plan_samples} samples"), nodes[-1]


def _plan_words(plan: AbstractPlan[S, A]) -> tuple[str, ...]:
    """A plan's actions as text: a plan enumerated again after learning has actions with more
    preconditions, but is the same plan."""
    return tuple(str(action) for action in plan.actions)


def _counted_plans(attempts: list[PlanAttempt[S, A]]) -> int:
    """The abstract plans that count against ``max_plans``: a plan dropped because a fact it
    taught rules it out does not (see ``SesameBudgets.max_plans``)."""
    return sum(attempt.outcome is not Outcome.PLAN_REFUTED for attempt in attempts)


def sesame(
    problem: BilevelProblem[X, U, S, A],
    budgets: SesameBudgets = DEFAULT_BUDGETS,
    *,
    seed: int = 0,
    on_sample: SampleCallback[S, A] | None = None,
    planner: str = "sesame",
) -> BilevelResult[X, U, S, A]:
    """Try abstract plans best first, refining each with backtracking, until one is refined
    or a budget of ``budgets`` runs out. The seed fixes both the order of equally good
    abstract plans and every sample.
    """
    max_plans = budgets.max_plans
    plan_seed, sample_seed = np.random.SeedSequence(seed).spawn(2)
    session = SamplingSession(problem, np.random.default_rng(sample_seed),
                              Budget(budgets.max_samples, budgets.time_budget_s), on_sample)
    learning = _Learning(plan_generator_of(problem), [])
    initial, plan_rng = session.graph.abstract_state_of(session.root), np.random.default_rng(plan_seed)
    plans = learning.generator(initial, plan_rng)
    known = 0  # facts the current enumeration was started with
    attempts: list[PlanAttempt[S, A]] = []

    def result(outcome: Outcome, detail: str, node: int | None = None) -> BilevelResult[X, U, S, A]:
        counts = PlanningCounts(
            samples=session.samples,
            failures=session.failures,
            backtracks=sum(step.backtracks for attempt in attempts for step in attempt.steps),
            abstract_plans=len(attempts),
        )
        plan = None if node is None else session.refined_plan(node)
        return BilevelResult(planner, plan, session.graph, counts, tuple(attempts), outcome, detail,
                             session.elapsed(), tuple(learning.facts))

    def failure_detail(outcome: Outcome) -> str:
        tried = f"{outcome.value} after {len(attempts)} abstract plan(s)"
        return f"{tried}; last: {attempts[-1].detail}" if attempts else tried

    while True:
        if max_plans is not None and _counted_plans(attempts) >= max_plans:
            return result(Outcome.PLAN_BUDGET, failure_detail(Outcome.PLAN_BUDGET))
        spent = session.budget_spent()
        if spent is not None:
            return result(spent, failure_detail(spent))
        if len(learning.facts) > known:  # plan again with what the failures taught
            plans, known = learning.generator(initial, plan_rng), len(learning.facts)
        tried = {_plan_words(attempt.abstract_plan) for attempt in attempts}
        abstract_plan = next((plan for plan in plans if _plan_words(plan) not in tried), None)
        if abstract_plan is None:
            return result(Outcome.NO_ABSTRACT_PLAN, failure_detail(Outcome.NO_ABSTRACT_PLAN))
        attempt, node = _refine_with_backtracking(session, abstract_plan, len(attempts), budgets, learning)
        attempts.append(attempt)
        if node is not None:
            return result(Outcome.SOLVED, f"abstract plan {len(attempts)}: {attempt.detail}", node)
        if attempt.outcome in (Outcome.SAMPLE_BUDGET, Outcome.TIME_BUDGET):
            return result(attempt.outcome, failure_detail(attempt.outcome))


def backtracking_refinement(
    problem: BilevelProblem[X, U, S, A],
    budgets: SesameBudgets = DEFAULT_BUDGETS,
    *,
    seed: int = 0,
    on_sample: SampleCallback[S, A] | None = None,
) -> BilevelResult[X, U, S, A]:
    """The first abstract plan only, refined with backtracking: SeSamE with ``max_plans=1``."""
    return sesame(problem, replace(budgets, max_plans=1), seed=seed, on_sample=on_sample,
                  planner="backtracking")


def greedy_refinement(
    problem: BilevelProblem[X, U, S, A],
    budgets: SesameBudgets = DEFAULT_BUDGETS,
    *,
    seed: int = 0,
    on_sample: SampleCallback[S, A] | None = None,
) -> BilevelResult[X, U, S, A]:
    """The first abstract plan, one sample per step, never revisited: SeSamE with
    ``max_plans=1, samples_per_step=1``."""
    return sesame(problem, replace(budgets, max_plans=1, samples_per_step=1), seed=seed, on_sample=on_sample,
                  planner="greedy")
