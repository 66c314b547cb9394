"""Reference answers by exhaustive search, for checking the real searches on tiny tasks."""

from __future__ import annotations

from collections import deque

from kitchen_tamp.planning import State, Task


def reachable_states(task: Task) -> set[State]:
    seen = {task.initial_state}
    frontier = deque(seen)
    while frontier:
        state = frontier.popleft()
        for _, child in task.successors(state):
            if child not in seen:
                seen.add(child)
                frontier.append(child)
    return seen


def goal_distances(task: Task) -> dict[State, int]:
    """Exact length of the shortest plan from every reachable state (absent: no plan)."""
    states = reachable_states(task)
    predecessors: dict[State, list[State]] = {s: [] for s in states}
    for state in states:
        for _, child in task.successors(state):
            predecessors[child].append(state)
    distance = {s: 0 for s in states if task.is_goal(s)}
    frontier = deque(distance)
    while frontier:
        state = frontier.popleft()
        for parent in predecessors[state]:
            if parent not in distance:
                distance[parent] = distance[state] + 1
                frontier.append(parent)
    return distance


def shortest_plan_length(task: Task) -> int | None:
    """Iterative deepening over action sequences: independent of every search we test."""
    for limit in range(0, 20):
        if _depth_limited(task, task.initial_state, limit, {task.initial_state}):
            return limit
    return None


def _depth_limited(task: Task, state: State, limit: int, path: set[State]) -> bool:
    if task.is_goal(state):
        return True
    if limit == 0:
        return False
    for _, child in task.successors(state):
        if child not in path:
            path.add(child)
            found = _depth_limited(task, child, limit - 1, path)
            path.discard(child)
            if found:
                return True
    return False
