"""Reference answers by exhaustive search, for checking the real searches on tiny tasks."""

from __future__ import annotations

from collections import deque
from itertools import product

from kitchen_tamp.planning import State, Task
from kitchen_tamp.planning.schemas import LiftedTask


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


def naive_ground_action_names(lifted: LiftedTask) -> set[tuple[str, tuple[str, ...]]]:
    """(name, args) of the relaxed-reachable actions, by trying every type-correct binding.

    Independent of the join-based grounder: enumerate all bindings, keep those
    whose equalities and static negative preconditions hold, then apply them
    ignoring deletes until no new fact appears.
    """
    fluent = {pred for s in lifted.schemas for pred, _ in (*s.add, *s.delete)}
    candidates = []
    for schema in lifted.schemas:
        for values in product(*schema.candidates):
            binding = dict(zip(schema.parameters, values, strict=True))

            def term(t: str, binding: dict[str, str] = binding) -> str:
                return binding[t] if t.startswith("?") else t

            if any(term(a) != term(b) for a, b in schema.equal):
                continue
            if any(term(a) == term(b) for a, b in schema.not_equal):
                continue
            if any(p not in fluent and (p, *map(term, ts)) in lifted.init for p, ts in schema.pre_neg):
                continue
            pre = {(p, *map(term, ts)) for p, ts in schema.pre}
            add = {(p, *map(term, ts)) for p, ts in schema.add}
            candidates.append(((schema.name, tuple(values)), pre, add))
    facts = set(lifted.init)
    reached: set[tuple[str, tuple[str, ...]]] = set()
    changed = True
    while changed:
        changed = False
        for key, pre, add in candidates:
            if key not in reached and pre <= facts:
                reached.add(key)
                facts |= add
                changed = True
    return reached
