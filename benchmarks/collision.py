"""PyBullet against Drake collision checking of the kitchen arm, on the same configurations.

For the kitchen of ``pddl/problem.pddl`` with a free hand and holding the spam
box (as the pick skill grasps it), both checkers answer the same uniformly
random arm configurations: CPU time per configuration in one batch and per
single-configuration call (how OMPL asks), collision checks per second, how
often they agree, and how close to contact the disagreements are. The Drake
model's distance queries (for trajectory optimisation) are timed too.

    .venv/bin/python benchmarks/collision.py
    .venv/bin/python benchmarks/collision.py --configurations 5000 --seed 1
    .venv/bin/python benchmarks/collision.py --sphere-samples 100000   # sphere model vs PyBullet
    .venv/bin/python benchmarks/collision.py --dispatch   # what a call into the sphere kernel costs

With ``--sphere-samples N`` it instead checks the sphere model
(`kitchen_tamp.motion.geometry.spheres.checker`) against PyBullet, free-handed and
carrying each box the problem has: N uniform configurations and N near-obstacle
ones (bisected to within ~1 mm of PyBullet's contact between a free and a
colliding sample). Missed collisions (PyBullet colliding, spheres free) must be
zero; false positives (PyBullet free, spheres colliding) are reported as a
fraction of PyBullet's free configurations. Distance queries of the sphere model
(every pair with gradients) and Drake's (the minimum with its gradient) are timed.
With ``--dispatch`` it times calls into the sphere model's compiled kernel (``kernel_dispatch``).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from kitchen_tamp.kitchen import KitchenScene, SkillFailure, load_kitchen_problem, sample_targets
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.world import PyBulletCollisionChecker
from kitchen_tamp.world.scene_description import describe_collision_checker

PROBLEM = Path(__file__).resolve().parents[1] / "pddl" / "problem.pddl"

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
Validity = Callable[[FloatArray], BoolArray]


def drake_twin(checker: PyBulletCollisionChecker) -> DrakeCollisionChecker:
    """The Drake model of the scene ``checker`` captured, with its allowed contacts and margin."""
    description = describe_collision_checker(checker)
    return DrakeCollisionChecker(description, margin=checker.margin)


@dataclass(frozen=True)
class Timing:
    """One checker on one scene."""

    scene: str
    checker: str
    batch_us: float
    single_us: float
    valid_fraction: float


def cpu_us_per_configuration(validity: Validity, qs: FloatArray, batch: bool) -> tuple[float, BoolArray]:
    """(CPU microseconds per configuration, validity), best of three runs."""
    best, valid = np.inf, np.zeros(len(qs), dtype=bool)
    for _ in range(3):
        start = time.process_time()
        valid = validity(qs) if batch else np.array([validity(q[np.newaxis])[0] for q in qs], dtype=bool)
        best = min(best, time.process_time() - start)
    return best / len(qs) * 1e6, valid


def cpu_us_per_call(function: Callable[[FloatArray], object], qs: FloatArray) -> float:
    start = time.process_time()
    for q in qs:
        function(q)
    return (time.process_time() - start) / len(qs) * 1e6


def compare(
    scene: str, pybullet: PyBulletCollisionChecker, drake: DrakeCollisionChecker, qs: FloatArray
) -> list[str]:
    """Timings of both checkers and a paragraph on their agreement."""
    timings, verdicts = [], {}
    for name, validity in (("pybullet", pybullet.is_valid), ("drake", drake.is_valid)):
        batch_us, valid = cpu_us_per_configuration(validity, qs, batch=True)
        single_us, _ = cpu_us_per_configuration(validity, qs[:500], batch=False)
        timings.append(Timing(scene, name, batch_us, single_us, float(np.mean(valid))))
        verdicts[name] = valid
    differ = np.flatnonzero(verdicts["pybullet"] != verdicts["drake"])
    clearance = pybullet.min_clearance(qs[differ]) * 1e3
    distance = np.array([drake.min_distance(q) for q in qs[differ]]) * 1e3
    lines = [format_row(t) for t in timings]
    lines.append(
        f"{'':<10}agreement {1 - len(differ) / len(qs):.2%} ({len(differ)} of {len(qs)} differ: "
        f"{int(np.sum(verdicts['pybullet'][differ]))} valid only for PyBullet)"
    )
    if len(differ):
        lines.append(
            f"{'':<10}where they differ, PyBullet's clearance is {clearance.min():+.2f}.."
            f"{clearance.max():+.2f} mm and Drake's distance {distance.min():+.2f}..{distance.max():+.2f} mm"
        )
    near = qs[:200]
    lines.append(
        f"{'':<10}drake min_distance {cpu_us_per_call(drake.min_distance, near):.0f} us, "
        f"signed_distance {cpu_us_per_call(drake.signed_distance, near):.0f} us per call; "
        f"pybullet min_clearance {cpu_us_per_call(lambda q: pybullet.min_clearance(q), near):.0f} us"
    )
    return lines


HEADER = f"{'scene':<10}{'checker':<10}{'batch us/q':>12}{'single us/q':>13}{'checks/s':>11}{'valid':>8}"


def format_row(t: Timing) -> str:
    return (
        f"{t.scene:<10}{t.checker:<10}{t.batch_us:>12.1f}{t.single_us:>13.1f}"
        f"{1e6 / t.batch_us:>11.0f}{t.valid_fraction:>8.1%}"
    )


def near_obstacle(checker: PyBulletCollisionChecker, count: int, rng: np.random.Generator) -> FloatArray:
    """``count`` configurations near PyBullet's contact: free/colliding pairs bisected 12 times."""
    found_free, found_colliding = [], []
    while sum(map(len, found_free)) < count or sum(map(len, found_colliding)) < count:
        qs = rng.uniform(checker.lower, checker.upper, size=(4096, 7))
        valid = checker.is_valid(qs)
        found_free.append(qs[valid])
        found_colliding.append(qs[~valid])
    free, colliding = np.concatenate(found_free)[:count], np.concatenate(found_colliding)[:count]
    for _ in range(12):
        middle = (free + colliding) / 2.0
        middle_valid = checker.is_valid(middle)[:, None]
        free, colliding = np.where(middle_valid, middle, free), np.where(middle_valid, colliding, middle)
    return np.concatenate([free[: count // 2], colliding[: count - count // 2]])


def sphere_agreement(kitchen: KitchenScene, samples: int, seed: int) -> None:
    from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker

    rng = np.random.default_rng(seed)
    scenes = {"free hand": kitchen.collision_checker()}
    for box in sorted(kitchen.boxes):
        for surface in kitchen.map.surfaces:  # the box stands on one of them
            with kitchen.scene.preserved():
                try:
                    sample_targets(kitchen, "pickUp", (box, surface), rng).apply(kitchen)
                except SkillFailure:
                    continue
                if kitchen.held_box() == box:
                    scenes[f"carrying {box}"] = kitchen.collision_checker()
                    break
    print(f"sphere model vs PyBullet, {samples} uniform + {samples} near-obstacle configurations per scene")
    header = f"{'scene':<18}{'sample':<9}{'pyb free':>9}{'missed':>8}{'false pos':>10}"
    print(header + f"{'spheres/s':>12}{'pybullet/s':>12}")
    for name, checker in scenes.items():
        spheres = SphereCollisionChecker(describe_collision_checker(checker), margin=checker.margin)
        spheres.is_valid(np.zeros((1, 7)))
        for label, qs in (
            ("uniform", rng.uniform(checker.lower, checker.upper, size=(samples, 7))),
            ("near", near_obstacle(checker, samples, rng)),
        ):
            sphere_us, sphere_valid = cpu_us_per_configuration(spheres.is_valid, qs, batch=True)
            start = time.process_time()
            pybullet_valid = checker.is_valid(qs)
            pybullet_us = 1e6 * (time.process_time() - start) / len(qs)
            missed = int(np.sum(sphere_valid & ~pybullet_valid))
            false_positive = np.sum(~sphere_valid & pybullet_valid) / max(1, int(np.sum(pybullet_valid)))
            print(
                f"{name:<18}{label:<9}{pybullet_valid.mean():>9.3f}{missed:>8d}{false_positive:>10.3f}"
                f"{1e6 / sphere_us:>12,.0f}{1e6 / pybullet_us:>12,.0f}"
            )
    free = scenes["free hand"]
    spheres = SphereCollisionChecker(describe_collision_checker(free))
    drake = drake_twin(free)
    qs = rng.uniform(free.lower, free.upper, size=(300, 7))
    sphere_call = cpu_us_per_call(spheres.pair_distances, qs)
    drake_call = cpu_us_per_call(drake.signed_distance, qs)
    print(
        f"distance with gradient, per configuration: spheres (all {len(spheres.pairs)} pairs) "
        f"{sphere_call:.0f} us, Drake (closest pair) {drake_call:.0f} us"
    )


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--configurations", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--sphere-samples", type=int, default=0, metavar="N")
    parser.add_argument("--dispatch", action="store_true", help="time calls into the sphere kernel")
    args = parser.parse_args(argv)

    _, kitchen = load_kitchen_problem(PROBLEM)
    with kitchen:
        if args.dispatch:
            from kernel_dispatch import dispatch_report

            from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker

            description = describe_collision_checker(kitchen.collision_checker())
            print(dispatch_report(SphereCollisionChecker(description, margin=0.002), args.seed))
            return 0
        if args.sphere_samples:
            sphere_agreement(kitchen, args.sphere_samples, args.seed)
            return 0
        free = kitchen.collision_checker()
        with kitchen.scene.preserved():
            sample_targets(kitchen, "pickUp", ("spam", "countertop"), np.random.default_rng(args.seed)).apply(
                kitchen
            )
            holding = kitchen.collision_checker()
        start = time.perf_counter()
        twins = {"free": drake_twin(free), "holding": drake_twin(holding)}
        build_s = (time.perf_counter() - start) / 2
        qs = np.random.default_rng(args.seed).uniform(free.lower, free.upper, size=(args.configurations, 7))
        print(
            f"{args.configurations} random arm configurations of the {PROBLEM.name} kitchen, "
            f"seed {args.seed}; CPU time, best of 3; Drake model built in {build_s:.2f} s"
        )
        print(HEADER)
        print("-" * len(HEADER))
        for scene, checker in (("free", free), ("holding", holding)):
            print("\n".join(compare(scene, checker, twins[scene], qs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
