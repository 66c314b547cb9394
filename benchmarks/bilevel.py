"""The four bilevel planners on random toy rooms instances: success rate and median time.

Each instance is ``random_scene(i)`` (3 x 3 to 4 x 4 rooms, random doors,
crates in doorways, pillars hiding doorways, the goal the farthest room from
the start) and each planner runs on it with seed ``i``. Every planner gets the
same sample and time budgets; samples per step (SeSamE, backtracking) and per
abstract transition (abstract BFS) are the same K. Not every instance is
solvable, so no planner reaches 100%.

    python benchmarks/bilevel.py                  # 100 instances
    python benchmarks/bilevel.py --instances 20   # quicker
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from kitchen_tamp.bilevel import (
    BilevelProblem,
    BilevelResult,
    SesameBudgets,
    abstract_bfs,
    backtracking_refinement,
    greedy_refinement,
    sesame,
)
from kitchen_tamp.bilevel.toy_rooms import Passage, Point, random_scene

RoomsProblem = BilevelProblem[Point, Point, str, Passage]
RoomsResult = BilevelResult[Point, Point, str, Passage]

MAX_SAMPLES = 500
TIME_BUDGET_S = 5.0
K = 10
SESAME_SAMPLES_PER_PLAN = 100


@dataclass(frozen=True)
class Planner:
    name: str
    budgets: str
    run: Callable[[RoomsProblem, int], RoomsResult]


PLANNERS = (
    Planner("abstract BFS", f"N={K}, {MAX_SAMPLES} samples",
            lambda problem, seed: abstract_bfs(problem, seed=seed, samples_per_transition=K,
                                               max_samples=MAX_SAMPLES, time_budget_s=TIME_BUDGET_S)),
    Planner("greedy", "1 plan, K=1",
            lambda problem, seed: greedy_refinement(
                problem, SesameBudgets(time_budget_s=TIME_BUDGET_S), seed=seed)),
    Planner("backtracking", f"1 plan, K={K}, {MAX_SAMPLES} samples",
            lambda problem, seed: backtracking_refinement(
                problem,
                SesameBudgets(samples_per_step=K, max_samples=MAX_SAMPLES, time_budget_s=TIME_BUDGET_S),
                seed=seed)),
    Planner("SeSamE", f"K={K}, {SESAME_SAMPLES_PER_PLAN}/plan, {MAX_SAMPLES} samples",
            lambda problem, seed: sesame(
                problem, SesameBudgets(max_plans=None, samples_per_step=K, max_samples=MAX_SAMPLES,
                                       max_samples_per_plan=SESAME_SAMPLES_PER_PLAN,
                                       time_budget_s=TIME_BUDGET_S),
                seed=seed)),
)


@dataclass
class Tally:
    """One planner's results over all instances."""

    solved: int = 0
    seconds: list[float] = field(default_factory=list)
    samples: list[int] = field(default_factory=list)
    plans: list[int] = field(default_factory=list)

    def add(self, result: RoomsResult, seconds: float) -> None:
        self.solved += result.solved
        self.seconds.append(seconds)
        self.samples.append(result.counts.samples)
        self.plans.append(result.counts.abstract_plans)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--instances", type=int, default=100, help="number of random instances (default 100)")
    args = parser.parse_args()

    tallies = {planner.name: Tally() for planner in PLANNERS}
    solved_by_any = 0
    for index in range(args.instances):
        problem = random_scene(index).problem()
        solved = False
        for planner in PLANNERS:
            start = time.perf_counter()
            result = planner.run(problem, index)
            tallies[planner.name].add(result, time.perf_counter() - start)
            solved = solved or result.solved
        solved_by_any += solved

    print(f"{args.instances} random toy rooms instances (random_scene(0..{args.instances - 1})), "
          f"planner seed = instance index, time budget {TIME_BUDGET_S:g} s each\n")
    header = f"| {'planner':<13} | {'budgets':<31} | success | median time | median samples | median plans |"
    print(header)
    print("|" + "|".join("-" * len(cell) for cell in header.split("|")[1:-1]) + "|")
    for planner in PLANNERS:
        tally = tallies[planner.name]
        rate = 100.0 * tally.solved / args.instances
        seconds = statistics.median(tally.seconds) * 1000
        samples = statistics.median(tally.samples)
        plans = f"{statistics.median(tally.plans):g}" if planner.name != "abstract BFS" else "-"
        print(f"| {planner.name:<13} | {planner.budgets:<31} | {rate:6.0f}% | {seconds:8.2f} ms | "
              f"{samples:14g} | {plans:>12} |")
    print(f"\nsolved by at least one planner: {100.0 * solved_by_any / args.instances:.0f}%")


if __name__ == "__main__":
    main()
