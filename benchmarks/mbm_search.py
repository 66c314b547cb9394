"""Our RRT-Connect alone on MotionBenchMaker's problems, over steps and tree balances.

    .venv/bin/python benchmarks/mbm_search.py bookshelf_small --problems 100 --steps 0.3 1 --balances 0 1.5
    .venv/bin/python benchmarks/mbm_search.py bookshelf_small --problems 30 --python-loop

Per setting: median, mean and 95th percentile of planning CPU milliseconds (a failure counted at
the budget) and the failures, with the sphere model as `benchmarks/motion.py --query-set mbm`
plans (`mbm_motion.mbm_case`), seeded as it seeds (seed + the problem's number), no smoothing and
no judge; the runs of one problem follow each other, so a setting is not favoured by the load.
With ``--python-loop`` each setting is also run through the Python loop (the same search: the
sphere model with its compiled validity hidden, `PythonLoopSpheres`).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from mbm_motion import MBM_SEARCH, mbm_case
from mbm_problems import load_problems

from kitchen_tamp.motion import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    RrtConnectHyperparameters,
    ValidityMask,
    plan_rrt_connect,
)
from kitchen_tamp.motion.motion_bench_maker import MBM_SCENARIOS


class PythonLoopSpheres:
    """A checker without `CompiledValidity`, so `plan_rrt_connect` runs its Python loop; every call
    goes to the wrapped one (its compiled segment checks too)."""

    def __init__(self, checker: Any) -> None:
        self.checker = checker

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        return np.asarray(self.checker.is_valid(qs), dtype=np.bool_)

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return bool(self.checker.segment_valid(q0, q1))

    def segment_checked(self, *arguments: Any) -> tuple[bool, int]:
        free, checked = self.checker.segment_checked(*arguments)
        return bool(free), int(checked)

    def free_prefix_checked(self, *arguments: Any) -> tuple[float, int]:
        length, checked = self.checker.free_prefix_checked(*arguments)
        return float(length), int(checked)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scenario", choices=MBM_SCENARIOS)
    parser.add_argument("--problems", type=int, default=30)
    parser.add_argument("--steps", type=float, nargs="+", default=[MBM_SEARCH.step_size],
                        help="rad (default the benchmark's, %(default)s)")
    parser.add_argument("--balances", type=float, nargs="+", default=[MBM_SEARCH.tree_balance],
                        help="tree balances (default the benchmark's, %(default)s)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--budget", type=float, default=1.0, help="CPU seconds per problem")
    parser.add_argument("--python-loop", action="store_true", help="each setting through both loops")
    args = parser.parse_args(argv)
    loops = ("compiled", "python") if args.python_loop else ("compiled",)
    settings = [(step, balance, loop) for balance in args.balances for step in args.steps for loop in loops]
    times: dict[tuple[float, float, str], list[float]] = {setting: [] for setting in settings}
    for number, problem in enumerate(load_problems([args.scenario], args.problems)):
        with mbm_case(problem) as case:
            if number == 0:  # load the compiled kernels outside the clock
                plan_rrt_connect(problem.start, problem.goals[0], case.query.space, case.planning)
            for step, balance, loop in settings:
                checker: CollisionChecker = (
                    case.planning if loop == "compiled" else PythonLoopSpheres(case.planning)
                )
                search = RrtConnectHyperparameters(
                    step_size=step, tree_balance=balance, max_iterations=10**9, clock=time.process_time
                )
                cpu = time.process_time()
                planned = plan_rrt_connect(
                    problem.start,
                    problem.goals[0],
                    case.query.space,
                    checker,
                    search,
                    seed=args.seed + problem.index,
                    time_budget_s=args.budget,
                )
                spent = time.process_time() - cpu
                times[step, balance, loop].append(spent if planned.solved else args.budget)
                if not planned.solved:
                    print(f"  {problem.name} step {step} balance {balance} {loop}: {planned.status.value}")
    print(f"{args.scenario}, {args.problems} problems, seed {args.seed}; CPU ms, a failure at the budget")
    for (step, balance, loop), spent_s in times.items():
        ms = np.asarray(spent_s) * 1e3
        print(
            f"step {step:g} balance {balance:g} {loop} loop: median {np.median(ms):.2f}, "
            f"mean {ms.mean():.1f}, p95 {np.percentile(ms, 95):.0f}, "
            f"failures {int(np.sum(ms >= args.budget * 1e3))}/{len(ms)}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
