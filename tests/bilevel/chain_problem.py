"""A synthetic bilevel problem for exact counts: a chain of abstract states s0 -> s1 -> ... -> sn.

The low-level state is an int that counts the steps taken; the sampler of step
``i`` fails whenever ``failing(i, sample number)`` says so, and otherwise moves
to the next state. ``branches`` adds a second, longer route so that there is
more than one abstract plan.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np

from kitchen_tamp.bilevel import (
    Abstraction,
    AbstractTransition,
    BilevelProblem,
    SamplingFailure,
    Trajectory,
    TrajectorySampler,
)

ChainState = tuple[str, int]
"""(abstract state name, number of moves so far)."""


def chain_problem(
    length: int, failing: Callable[[str, int], bool], detour: bool = False
) -> BilevelProblem[ChainState, str, str, str]:
    """States s0..s{length}; with ``detour``, also s0 -> d1 -> d2 -> s{length}."""
    edges: dict[str, list[tuple[str, str]]] = {
        f"s{i}": [(f"s{i}->s{i + 1}", f"s{i + 1}")] for i in range(length)}
    if detour:
        edges["s0"].append(("s0->d1", "d1"))
        edges["d1"] = [("d1->d2", "d2")]
        edges["d2"] = [(f"d2->s{length}", f"s{length}")]
    tries: dict[str, int] = {}

    def successors(state: str) -> Iterator[tuple[str, str]]:
        yield from edges.get(state, [])

    def sampler(
        state: ChainState, transition: AbstractTransition[str, str], rng: np.random.Generator
    ) -> Trajectory[ChainState, str]:
        tries[transition.action] = tries.get(transition.action, 0) + 1
        if failing(transition.action, tries[transition.action]):
            raise SamplingFailure(f"{transition.action} refused sample {tries[transition.action]}")
        return Trajectory((state, (transition.target, state[1] + 1)), (transition.action,))

    chain_sampler: TrajectorySampler[ChainState, str, str, str] = sampler
    return BilevelProblem(
        initial_state=("s0", 0),
        abstraction=Abstraction(lambda x: x[0], successors, lambda s: s == f"s{length}"),
        sampler_for=lambda action: chain_sampler,
        transition=lambda x, u: (u.split("->")[1], x[1] + 1),
    )
