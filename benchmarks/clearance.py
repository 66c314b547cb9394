"""What trajectory optimisation pays per collision point: the sphere model's smooth clearance against
Drake's signed distance, both with joint gradients, on the same kitchen configurations.

For the kitchen of ``pddl/problem.pddl`` with a free hand and holding the spam box (as the pick
skill grasps it), uniformly random arm configurations that Drake finds free (with the pipeline's
3 mm planning margin) are answered by ``SphereClearance`` (every sphere pair, one compiled call
for the whole batch, as the optimiser's constraints ask) and by
``DrakeCollisionChecker.signed_distance`` (the closest pair and its gradient, one configuration
at a time, as before). CPU time per configuration and the ratio, in one run.

    .venv/bin/python benchmarks/clearance.py
    .venv/bin/python benchmarks/clearance.py --configurations 2000 --seed 1
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from kitchen_tamp.kitchen import KitchenScene, load_kitchen_problem, sample_targets
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.spheres.clearance import SphereClearance
from kitchen_tamp.motion.geometry.spheres.scene import SphereScene
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from kitchen_tamp.refinement.refine_action import PLANNING_MARGIN
from kitchen_tamp.world.scene_description import describe_collision_checker

PROBLEM = Path(__file__).resolve().parents[1] / "pddl" / "problem.pddl"


def measure(kitchen: KitchenScene, label: str, count: int, rng: np.random.Generator) -> str:
    description = describe_collision_checker(kitchen.collision_checker())
    drake = DrakeCollisionChecker(description, margin=PLANNING_MARGIN)
    clearance = SphereClearance(SphereScene(description), DEFAULT_SETTINGS.collision_margin)
    samples = rng.uniform(drake.lower, drake.upper, size=(20 * count, 7))
    free = samples[drake.is_valid(samples)][:count]
    clearance(free[:1])  # load the compiled kernel before timing it
    repeats = 10
    clock = time.process_time()
    for _ in range(repeats):
        clearance(free)
    spheres_us = (time.process_time() - clock) / repeats / len(free) * 1e6
    clock = time.process_time()
    for q in free:
        drake.signed_distance(q)
    drake_us = (time.process_time() - clock) / len(free) * 1e6
    return (
        f"| {label} | {len(free)} | {spheres_us:.1f} | {drake_us:.1f} | {drake_us / spheres_us:.1f}x |"
    )


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n")[0])
    parser.add_argument("--configurations", type=int, default=500, help="free configurations per scene")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    _, kitchen = load_kitchen_problem(PROBLEM)
    rows = []
    with kitchen:
        rows.append(measure(kitchen, "free hand", args.configurations, rng))
        with kitchen.scene.preserved():
            sample_targets(kitchen, "pickUp", ("spam", "countertop"), np.random.default_rng(args.seed)).apply(
                kitchen
            )
            rows.append(measure(kitchen, "holding spam", args.configurations, rng))
    print("CPU time per configuration, clearance (or signed distance) with its joint gradient")
    print()
    print("| scene | configurations | sphere clearance, µs (batched) | Drake signed distance, µs | ratio |")
    print("|---|---:|---:|---:|---:|")
    print("\n".join(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
