"""Closing the loop: when the simulated scene drifts from the plan beyond tolerance, refine
the rest of the plan again from the scene as it is.

The simulated scene is copied into a fresh kinematic kitchen (boxes where physics left
them, drawers as open as they are, the arm where it stands), the task's initial state
becomes the state the plan has reached (Ψ agreed with it), and a ``Replanner`` (SeSamE
with the run's motion back end, supplied by the caller: ``execute`` does not plan)
refines the remaining actions from there.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from kitchen_tamp.execute.physics.plan import PlannedOutcome, planned_outcomes
from kitchen_tamp.kitchen import RESTING_GAP, KitchenScene, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import State, Task

Replanner = Callable[[KitchenScene, Task], KitchenTrajectory | None]
"""``replan(kitchen, task)``: a refined trajectory from ``kitchen`` as it is to ``task``'s
goal (``task.initial_state`` is the symbolic state of ``kitchen``), or None."""


@dataclass(frozen=True, eq=False)
class Replan:
    """The rest of the plan refined again from the simulated scene."""

    trajectory: KitchenTrajectory
    outcomes: list[PlannedOutcome]


def observed_kitchen(task: Task, simulated: KitchenScene) -> KitchenScene:
    """A fresh kinematic kitchen for ``task`` laid out as ``simulated`` is now (hand empty).

    Loose boxes are lifted by the kitchen's resting gap, as the layout puts them, and a
    box inside a drawer rides with it again.
    """
    observed = build_kitchen_for_task(task, kitchen_map=simulated.map)
    try:
        for body in observed.boxes.values():
            observed.scene.detach(body)
        for openable in observed.map.openables:
            observed.set_opening(openable, simulated.opening(openable))
        for name, body in observed.boxes.items():
            resting = simulated.box(name).base_pose().translated((0.0, 0.0, RESTING_GAP))
            observed.scene.set_base_pose(body, resting)
        observed.robot.set_configuration(simulated.robot.configuration())
        observed.robot.set_gripper_width(simulated.robot.gripper_width())
        for name in observed.boxes:
            observed.settle(name)
    except BaseException:
        observed.close()
        raise
    return observed


def replan_rest(task: Task, state: State, simulated: KitchenScene, replan: Replanner) -> Replan | None:
    """The remaining actions from ``state`` refined again from the simulated scene, with the
    poses they plan for, or None if the replanner found none."""
    rest_task = task.starting_from(state)
    with observed_kitchen(task, simulated) as observed:
        start = observed.scene.save_state()
        trajectory = replan(observed, rest_task)
        if trajectory is None or not trajectory.steps:
            return None
        observed.scene.restore_state(start)
        return Replan(trajectory, planned_outcomes(observed, rest_task, trajectory))
