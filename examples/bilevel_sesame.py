"""SeSamE switching abstract plans: the blocked-doorway scene.

The shortest abstract plan A -> B -> C does not know about the crate in door
B-C. Refining it with backtracking fails every way it can; SeSamE then takes
the next abstract plan, A -> D -> E -> F -> C, and refines it.

    python examples/bilevel_sesame.py   # writes docs/assets/bilevel_sesame.gif
"""

from __future__ import annotations

from toy_rooms_drawing import ASSETS, GrowthRenderer, RoomsEvent

from kitchen_tamp.bilevel import SesameBudgets, sesame
from kitchen_tamp.bilevel.toy_rooms import blocked_doorway

SAMPLES_PER_STEP = 4


def main() -> None:
    scene = blocked_doorway()
    events: list[RoomsEvent] = []
    result = sesame(scene.problem(), SesameBudgets(samples_per_step=SAMPLES_PER_STEP), seed=0,
                    on_sample=events.append)
    for attempt in result.attempts:
        print(f"plan {attempt.index + 1} {' -> '.join(attempt.abstract_plan.states)}: {attempt.detail}")
    renderer = GrowthRenderer(scene, result, events, f"SeSamE, K = {SAMPLES_PER_STEP} (seed 0)")
    renderer.write_gif(ASSETS / "bilevel_sesame.gif", frame_ms=300)


if __name__ == "__main__":
    main()
