"""States of seeded random walks through a task's state space: samples for comparing heuristics."""

from __future__ import annotations

import random

from kitchen_tamp.planning.task import State, Task


def random_walk_states(task: Task, seed: int, walks: int, length: int) -> list[State]:
    """The initial state, then the states of ``walks`` seeded random walks of at most ``length`` steps
    from it (a walk ends early at a dead end)."""
    chooser = random.Random(seed)
    states = [task.initial_state]
    for _ in range(walks):
        state = task.initial_state
        for _ in range(length):
            children = [child for child, _ in task.successor_indices(state)]
            if not children:
                break
            state = chooser.choice(children)
            states.append(state)
    return states
