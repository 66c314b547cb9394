"""Abstract BFS growing its planning graph through nine rooms.

Rooms are expanded in breadth-first order from G; each abstract transition
gets three samples, from the low-level states already in its room. Shaded rooms
are the abstract states reached so far; door B-C holds a crate and a pillar
hides door C-F from part of room F.

    python examples/bilevel_abstract_bfs.py   # writes docs/assets/bilevel_abstract_bfs.gif
"""

from __future__ import annotations

from toy_rooms_drawing import ASSETS, GrowthRenderer, RoomsEvent, Shadow

from kitchen_tamp.bilevel import abstract_bfs
from kitchen_tamp.bilevel.toy_rooms import nine_rooms


def main() -> None:
    scene = nine_rooms()
    events: list[RoomsEvent] = []
    result = abstract_bfs(scene.problem(), seed=1, on_sample=events.append)
    print(f"abstract BFS, seed 1: {result.outcome.value}; {result.detail}; {result.counts}")
    renderer = GrowthRenderer(scene, result, events, "Abstract BFS, N = 3 (seed 1)",
                              shadows=[Shadow("F", "C-F")])
    renderer.write_gif(ASSETS / "bilevel_abstract_bfs.gif", frame_ms=300)


if __name__ == "__main__":
    main()
