"""process: an action that needs a box where it rests, and no motion (wash it in the sink, cook it
on a burner). The box must rest on the ``place`` the action names; the arm holds still. What the
action does to the box (``clean``, ``cooked``) its effects say, and the refinement records them
as conditions (``kitchen_tamp.kitchen.conditions``)."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.kitchen.binding import ActionBinding
from kitchen_tamp.kitchen.conditions import process_problem
from kitchen_tamp.kitchen.errors import FailureKind, SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.straight_moves import hold_still
from kitchen_tamp.kitchen.skills.targets import SkillTargets, action_text

PROCESS_SEGMENT = "process"


def sample_process(
    kitchen: KitchenScene,
    action: tuple[str, tuple[str, ...]],
    binding: ActionBinding,
    rng: np.random.Generator,
    parameters: SkillParameters,
) -> SkillTargets:
    """Targets that keep the arm where it is, if the ``object`` rests on the ``place``."""
    text = action_text(action)
    box, place = binding.argument("object", action[1]), binding.argument("place", action[1])
    assert box is not None and place is not None  # required roles
    problem = process_problem(kitchen, box, place)
    if problem is not None:
        raise SkillFailure(text, problem, FailureKind.PRECONDITION, (box,), place)
    q = kitchen.arm_configuration()
    width = kitchen.robot.gripper_width()
    still, widths = hold_still(q, (width, width))
    return SkillTargets(
        action=action,
        goal_configuration=q,
        held_box=kitchen.held_box(),
        gripper_width=width,
        segments=(Segment(PROCESS_SEGMENT, still, widths),),
        free_space_checker=kitchen.collision_checker(),
        samples_tried=1,
    )
