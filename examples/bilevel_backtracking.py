"""Backtracking refinement where greedy refinement fails: the pillar-shadow scene, seed 1.

The first landing in room B is in the pillar's shadow, so every sample of
B -> C fails; after K of them the planner steps back and samples A -> B again,
until it lands where door B-C is in sight.

    python examples/bilevel_backtracking.py   # writes docs/assets/bilevel_backtracking.gif
"""

from __future__ import annotations

from toy_rooms_drawing import ASSETS, GrowthRenderer, RoomsEvent, Shadow

from kitchen_tamp.bilevel import SesameBudgets, backtracking_refinement
from kitchen_tamp.bilevel.toy_rooms import pillar_shadow

SAMPLES_PER_STEP = 4


def main() -> None:
    scene = pillar_shadow()
    events: list[RoomsEvent] = []
    budgets = SesameBudgets(samples_per_step=SAMPLES_PER_STEP)
    result = backtracking_refinement(scene.problem(), budgets, seed=1, on_sample=events.append)
    print(f"backtracking, seed 1, K={SAMPLES_PER_STEP}: {result.outcome.value}; {result.detail}; "
          f"{result.counts}")
    renderer = GrowthRenderer(scene, result, events, f"Backtracking, K = {SAMPLES_PER_STEP} (seed 1)",
                              shadows=[Shadow("B", "B-C")])
    renderer.write_gif(ASSETS / "bilevel_backtracking.gif", frame_ms=450)


if __name__ == "__main__":
    main()
