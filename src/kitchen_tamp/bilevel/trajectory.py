"""Low-level trajectories: the states a sampler passes through and the actions between them."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Generic, TypeVar

X = TypeVar("X")
U = TypeVar("U")


@dataclass(frozen=True, eq=False)
class Trajectory(Generic[X, U]):
    """States ``x_0 .. x_n`` and the actions ``u_0 .. u_{n-1}`` that lead from each to the next.

    The library only holds references to the states: they need not be hashable,
    comparable or cheap to copy (a simulator snapshot is fine). ``x_0`` is the
    state the sampler was given; the last state is where the abstract action ends.
    """

    states: tuple[X, ...]
    actions: tuple[U, ...]

    def __post_init__(self) -> None:
        if not self.states:
            raise ValueError("a trajectory needs at least its start state")
        if len(self.states) != len(self.actions) + 1:
            raise ValueError(
                f"a trajectory with {len(self.actions)} actions needs {len(self.actions) + 1} states, "
                f"got {len(self.states)}"
            )

    @property
    def initial_state(self) -> X:
        return self.states[0]

    @property
    def final_state(self) -> X:
        return self.states[-1]

    def __len__(self) -> int:
        """The number of actions."""
        return len(self.actions)


def rollout(transition: Callable[[X, U], X], state: X, actions: Iterable[U]) -> Trajectory[X, U]:
    """The trajectory that applying ``actions`` from ``state`` through ``transition`` produces."""
    states = [state]
    taken: list[U] = []
    for action in actions:
        states.append(transition(states[-1], action))
        taken.append(action)
    return Trajectory(tuple(states), tuple(taken))


def concatenate(trajectories: Sequence[Trajectory[X, U]], start: X) -> Trajectory[X, U]:
    """One trajectory through all of ``trajectories`` in order (``start`` if there are none).

    Each trajectory's start state is dropped after the first, since it is the
    previous one's final state.
    """
    states: list[X] = [trajectories[0].initial_state if trajectories else start]
    actions: list[U] = []
    for trajectory in trajectories:
        states.extend(trajectory.states[1:])
        actions.extend(trajectory.actions)
    return Trajectory(tuple(states), tuple(actions))
