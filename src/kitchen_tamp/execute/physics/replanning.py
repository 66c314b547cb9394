"""Closing the loop in a planning run: when the simulated scene drifts from the plan beyond
tolerance, refine the rest of the plan again from the scene as it is.

The simulated scene is copied into a fresh kinematic kitchen (boxes where physics left
them, drawers as open as they are, the arm where it stands), the task's initial state
becomes the state the plan has reached (Ψ agreed with it), and a ``Replanner`` (SeSamE
with the run's motion back end, supplied by the caller: ``execute`` does not plan)
refines the remaining actions from there. The planning run writes them into the
trajectory file and judges the file again; ``replay`` never re-plans.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from kitchen_tamp.kitchen import RESTING_GAP, KitchenScene, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import State, Task
from kitchen_tamp.world import FloatArray

Replanner = Callable[[KitchenScene, Task], KitchenTrajectory | None]
"""``replan(kitchen, task)``: a refined trajectory from ``kitchen`` as it is to ``task``'s
goal (``task.initial_state`` is the symbolic state of ``kitchen``), or None."""


@dataclass(frozen=True, eq=False)
class ArmState:
    """Where the plan leaves the arm: its configuration and the fingers' opening."""

    configuration: FloatArray
    gripper_width: float


def observed_kitchen(task: Task, simulated: KitchenScene, arm: ArmState) -> KitchenScene:
    """A fresh kinematic kitchen for ``task`` laid out as ``simulated`` is now (hand empty), the
    arm in ``arm`` (where the plan left it, so that the rest of the plan continues the file).

    Loose boxes are lifted by the kitchen's resting gap, as the layout puts them, and a
    box inside a drawer rides with it again.
    """
    observed = build_kitchen_for_task(task, kitchen_map=simulated.map, visuals=False)
    try:
        for body in observed.boxes.values():
            observed.scene.detach(body)
        for openable in observed.map.openables:
            observed.set_opening(openable, simulated.opening(openable))
        for name, body in observed.boxes.items():
            resting = simulated.box(name).base_pose().translated((0.0, 0.0, RESTING_GAP))
            observed.scene.set_base_pose(body, resting)
        observed.robot.set_configuration(arm.configuration)
        observed.robot.set_gripper_width(arm.gripper_width)
        for name in observed.boxes:
            observed.settle(name)
    except BaseException:
        observed.close()
        raise
    return observed


def replan_rest(
    task: Task, state: State, simulated: KitchenScene, arm: ArmState, replan: Replanner
) -> KitchenTrajectory | None:
    """The remaining actions from ``state`` refined again from the simulated scene (the arm in
    ``arm``), or None if the replanner found none."""
    with observed_kitchen(task, simulated, arm) as observed:
        trajectory = replan(observed, task.starting_from(state))
    return None if trajectory is None or not trajectory.steps else trajectory
