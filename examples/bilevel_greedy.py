"""Greedy refinement on the pillar-shadow scene, once lucky and once not.

One abstract plan (A -> B -> C), one sample per step. With seed 0 the robot
lands in room B where it can see door B-C and goes on; with seed 1 it lands in
the pillar's shadow (grey), the straight way to door B-C is blocked, and greedy
refinement has nothing to fall back on.

    python examples/bilevel_greedy.py   # writes docs/assets/bilevel_greedy_{success,failure}.gif
"""

from __future__ import annotations

from toy_rooms_drawing import ASSETS, GrowthRenderer, RoomsEvent, Shadow

from kitchen_tamp.bilevel import greedy_refinement
from kitchen_tamp.bilevel.toy_rooms import pillar_shadow


def main() -> None:
    scene = pillar_shadow()
    for seed, name in ((0, "success"), (1, "failure")):
        events: list[RoomsEvent] = []
        result = greedy_refinement(scene.problem(), seed=seed, on_sample=events.append)
        print(f"greedy, seed {seed}: {result.outcome.value}; {result.detail}")
        renderer = GrowthRenderer(scene, result, events, f"Greedy refinement (seed {seed})",
                                  shadows=[Shadow("B", "B-C")])
        renderer.write_gif(ASSETS / f"bilevel_greedy_{name}.gif", frame_ms=900)


if __name__ == "__main__":
    main()
