"""Execution under physics: run a trajectory in a fresh simulated kitchen and compare the
scene with the plan, as the kinematic judge read it, after every action.

The arm follows the trajectory's configurations on a time law within its
velocity limits, under position control; the fingers are commanded the planned
widths, pressing with a bounded force where the judge's tracks say they hold
something (``rollout``), so a box is held by friction and nothing else, and a
drawer moves only because the hand pulls its handle. Along the way the arm's lag
behind its command is bounded and every unplanned contact of the robot is a
problem. After each action the scene settles; then Ψ(scene) must be the planned
state, and every box and drawer must lie within the tolerances of where the
kinematic judge left it (position and tilt: Ψ alone would call a box leaning 30
degrees "on" the surface it leans on), and every stack the plan has standing must
stand (its top box on its base). Conditions (``clean``, ``cooked``) are derived in
the simulated scene as the planner derives them (``kitchen.record_conditions``).
Only the file's decisions are used: the actions' text and the segments'
configurations and gripper widths, read once by the kinematic judge
(``Verification.tracks`` and ``outcomes``) for both judges.

Physics judges what is in the file: it never plans. Given a ``Replanner`` (a
planning run), a scene that drifted beyond tolerance after an action stops the
execution with the rest of the plan refined again from the simulated scene
(``PhysicsExecution.replan``); the planning run writes those steps into the file
and judges the file again (``kitchen_tamp.execute.judging``).
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator

from kitchen_tamp.execute.atom_comparison import atoms_text, goal_literals
from kitchen_tamp.execute.physics.replanning import ArmState, Replanner, replan_rest
from kitchen_tamp.execute.physics.rollout import FrameCallback, Rollout
from kitchen_tamp.execute.physics.verdict import (
    DEFAULT_CONFIGURATION,
    PhysicsConfiguration,
    PhysicsExecution,
    Replan,
)
from kitchen_tamp.execute.run_report import RunReport
from kitchen_tamp.execute.verification import JudgedStep, Verification, judged_steps, parse_action
from kitchen_tamp.kitchen import KitchenMap, KitchenScene, build_kitchen_for_task, record_conditions
from kitchen_tamp.kitchen.abstraction import supports_of
from kitchen_tamp.kitchen.trajectory import ActionTrajectory, KitchenTrajectory
from kitchen_tamp.planning import Atom, Task
from kitchen_tamp.world.physics import PhysicsWorld

JudgedPair = tuple[ActionTrajectory, JudgedStep]
"""A step of the file and how the kinematic judge read it."""


def judged_pairs(trajectory: KitchenTrajectory, judged: Verification) -> Iterator[JudgedPair]:
    """The steps of ``trajectory`` with the judge's reading of each (from a finished verification)."""
    return zip(trajectory.steps, judged_steps(judged), strict=True)


def execute_under_physics(
    task: Task,
    steps: Iterable[JudgedPair],
    kitchen_map: KitchenMap | None = None,
    configuration: PhysicsConfiguration = DEFAULT_CONFIGURATION,
    on_frame: FrameCallback | None = None,
    replan: Replanner | None = None,
) -> PhysicsExecution:
    """Run the file's ``steps`` (each with the kinematic judge's reading of it) in a fresh
    simulated kitchen for ``task`` and judge them. ``steps`` may come as the judge reads them
    (`verify_trajectory`'s ``on_judged``): each is taken only when its action is executed.

    With ``replan``, a scene that has drifted beyond tolerance after an action (Ψ still as
    planned, hand empty, actions left) stops the execution with ``replan``'s refinement of
    the rest of the plan from the scene as it is (``PhysicsExecution.replan``)."""
    result = PhysicsExecution(configuration)
    settings = configuration.settings
    with build_kitchen_for_task(
        task, kitchen_map=kitchen_map, polyhedral_contacts=settings.polyhedral_contacts,
        visuals=on_frame is not None,  # only a recorded rollout is looked at
    ) as kitchen:
        world = PhysicsWorld(
            kitchen.scene, kitchen.robot, [kitchen.kitchen], list(kitchen.boxes.values()),
            settings,
        )
        rollout = Rollout(kitchen, world, result, dict(task.objects), on_frame)
        rollout.settle()
        state = task.initial_state
        coming = iter(steps)
        index, current = 0, next(coming, None)
        while current is not None:
            step, (tracks, outcome) = current
            figures = rollout.run_action(index, step, tracks, outcome)
            action = parse_action(task, step.action)
            if action is not None and action.applicable(state):
                state = action.apply(state)
            world.command_arm(step.end)
            rollout.settle()
            label, planned = f"after {step.action}", task.state_atoms(state)
            condition_problem = None if action is None else record_conditions(kitchen, task, action)
            result.problems.extend([f"{label}: {condition_problem}"] if condition_problem else [])
            result.problems.extend(f"{label}: {fallen}" for fallen in fallen_stacks(kitchen, planned))
            drift = rollout.compare(figures, outcome, planned)
            result.actions.append(figures)
            result.problems.extend(drift)
            index, current = index + 1, next(coming, None)  # asked only now: it may still be coming
            steady = figures.as_planned and figures.held_box is None and current is not None
            if drift and replan is not None and steady:
                arm = ArmState(step.end, float(step.segments[-1].gripper_widths[-1]))
                again = replan_rest(task, state, kitchen, arm, replan)
                result.replan = Replan(index, "; ".join(drift), again)
                break
        final = rollout.observed_atoms()
        result.final_atoms = atoms_text(final)
        result.goal_atoms = goal_literals(task, final)
        if result.actions:
            result.final_box_errors = result.actions[-1].box_errors
        result.simulated_s = world.time
    return result


def fallen_stacks(kitchen: KitchenScene, expected: frozenset[Atom]) -> list[str]:
    """The stacks the plan has standing (atoms of a predicate meaning ``on_box``, per the
    binding) whose top box no longer rests on its base in the simulated scene."""
    on_box = set(kitchen.map.binding.predicates_for("on_box"))
    fallen = []
    for atom in sorted(expected):
        if atom[0] in on_box and len(atom) == 3 and atom[2] in kitchen.boxes:
            top, base = atom[1], atom[2]
            resting = [name for _, name in supports_of(kitchen, top)]
            if base not in resting:
                fallen.append(f"the stack of {top} on {base} fell ({top} rests on "
                              f"{' and '.join(resting) or 'nothing'})")
    return fallen


def judge_under_physics(
    task: Task,
    trajectory: KitchenTrajectory,
    judged: Verification,
    report: RunReport,
    kitchen_map: KitchenMap | None = None,
    on_frame: FrameCallback | None = None,
    replan: Replanner | None = None,
) -> PhysicsExecution:
    """Execute ``trajectory`` under physics (in the kitchen of ``kitchen_map``, the default one
    if None) and record the verdict in ``report``: its ``physics`` section,
    ``timing.physics_s`` and, if physics failed, the run's failure."""
    clock = time.perf_counter()
    execution = execute_under_physics(task, judged_pairs(trajectory, judged), kitchen_map, on_frame=on_frame,
                                      replan=replan)
    report.timing["physics_s"] = report_seconds(report, "physics_s") + time.perf_counter() - clock
    report.physics = execution.report_data()
    if not execution.verified and execution.replan is None:
        report.fail("physics", "; ".join(execution.problems[:3]) or "the goal does not hold under physics")
    return execution


def report_seconds(report: RunReport, key: str) -> float:
    """Seconds already recorded under ``timing[key]`` (0 when none)."""
    value = report.timing.get(key, 0.0)
    return float(value) if isinstance(value, int | float) else 0.0
