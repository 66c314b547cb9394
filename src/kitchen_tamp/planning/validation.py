"""Replaying a plan against a task: the independent check of every search's output."""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from kitchen_tamp.planning.task import Atom, GroundAction, State, Task, atom_text, bits

PlanStep = tuple[str, tuple[str, ...]]


@dataclass(frozen=True, slots=True)
class PlanValidation:
    """Whether a plan is valid, why not, the state it ends in and the step that failed (1-based)."""

    valid: bool
    message: str
    final_state: State
    failed_step: int | None = None


def _as_step(step: GroundAction | PlanStep) -> PlanStep:
    if isinstance(step, GroundAction):
        return step.name, step.args
    return step


def validate_plan(task: Task, plan: Iterable[GroundAction | PlanStep]) -> PlanValidation:
    """Apply the plan from the initial state, checking every precondition and the goal."""
    state = task.initial_state
    actions = _actions_by_name(task)
    for number, raw in enumerate(plan, start=1):
        name, args = _as_step(raw)
        action = actions.get((name.lower(), tuple(a.lower() for a in args)))
        text = atom_text((name, *args))
        if action is None:
            schema_names = {a.name.lower() for a in task.actions}
            unknown = [a for a in args if a.lower() not in {o.lower() for o in task.objects}]
            why = (f"unknown object(s) {', '.join(unknown)}" if unknown else
                   f"unknown action '{name}'" if name.lower() not in schema_names else
                   "its preconditions can never hold")
            return PlanValidation(False, f"step {number} {text}: {why}", state, number)
        if not action.applicable(state):
            missing = [atom_text(task.atoms[i]) for i in bits(action.pre & ~state)]
            present = [atom_text(task.atoms[i]) for i in bits(action.pre_neg & state)]
            detail = "; ".join(filter(None, [
                "needs " + " ".join(missing) if missing else "",
                "needs not " + " ".join(present) if present else ""]))
            return PlanValidation(False, f"step {number} {text} is not applicable: {detail}",
                                  state, number)
        state = action.apply(state)
    if not task.is_goal(state):
        unmet = [atom_text(a) for a in sorted(goal_atoms_unmet(task, state))]
        return PlanValidation(False, "plan ends without reaching the goal: " + " ".join(unmet), state)
    return PlanValidation(True, "plan is valid", state)


def _actions_by_name(task: Task) -> dict[tuple[str, tuple[str, ...]], GroundAction]:
    """``Task.action_named`` for every step at once: the first action under each case-folded name.

    One pass over the actions instead of one per step (a 180-step plan on a
    task of a thousand actions took 30 ms).
    """
    index: dict[tuple[str, tuple[str, ...]], GroundAction] = {}
    for action in task.actions:
        index.setdefault((action.name.lower(), tuple(a.lower() for a in action.args)), action)
    return index


def goal_atoms_unmet(task: Task, state: State) -> set[Atom]:
    """Goal atoms false in ``state`` (and negated goal atoms true in it)."""
    true_atoms = task.state_atoms(state)
    unmet = {a for a in task.goal_atoms if a not in true_atoms and a not in _static_true(task)}
    unmet |= {("not", *a) for a in task.negative_goal_atoms if a in true_atoms}
    return unmet | set(task.unreachable_goal_atoms)


def _static_true(task: Task) -> frozenset[Atom]:
    fluent = {a[0] for a in task.atoms}
    return frozenset(a for a in task.init_atoms if a[0] not in fluent)


def plan_text(plan: Sequence[GroundAction]) -> str:
    """The IPC plan-file form: one ``(action arg ...)`` per line and a cost comment."""
    lines = [action.text for action in plan]
    lines.append(f"; cost = {len(plan)} (unit cost)")
    return "\n".join(lines) + "\n"


PLAN_STEP_PATTERN = r"^\s*\(([^()]+)\)\s*(;.*)?$"
"""One plan-file line: ``(name arg ...)`` and an optional ``;`` comment."""


def parse_plan_text(text: str) -> list[PlanStep]:
    """Read an IPC plan file: ``(name arg ...)`` lines; ``;`` comments and blank lines skipped."""
    step = re.compile(PLAN_STEP_PATTERN)
    steps: list[PlanStep] = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith(";"):
            continue
        match = step.match(line)
        if match is None:
            raise ValueError(f"line {number}: expected '(action arg ...)', got {line.strip()!r}")
        name, *args = match.group(1).split()
        steps.append((name, tuple(args)))
    return steps
