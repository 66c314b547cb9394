"""Confirming what a failed skill blames, before the planner builds on it.

A ``SkillFailure`` of kind ``obstructed`` names every box its refused candidates ran
into, most often first; some of them may only have been grazed by candidates that
failed for other reasons too. ``confirm_obstruction`` checks the names the way the
failure claims them: with all of them moved out of the scene the skill must find
targets (else nothing is confirmed); then they are put back one by one, the least
blamed first, and each one without which the skill still finds targets stays back.
What is left out is the obstruction: no box of it can come back on its own (as far
as the samples tell), and the boxes blamed most are the ones kept out.
``confirm_unreachable`` checks a placement that found nothing to blame: with every
other box moved out, the skill must still find no targets, and no pose of the empty
hand pointing down above the place may be within the arm's reach (a placement can
fail for the grasp the box is held by -- a long box held too low for a drawer -- and
the place is then not to blame).

Both leave the scene as they found it, and draw from the generator they are given
(the caller's own, so the planner's samples are not disturbed).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import replace
from typing import Final

import numpy as np

from kitchen_tamp.kitchen.errors import SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.layout import WORLD_FROM_TOOL_DOWN
from kitchen_tamp.kitchen.skills.parameters import DEFAULT_PARAMETERS, SkillParameters
from kitchen_tamp.kitchen.skills.registry import GroundedAction, sample_action_targets
from kitchen_tamp.world import Pose

PUT_BACK_ATTEMPTS: Final = 20
"""Candidates the check of a box put back draws (the check with every named box out draws the
skill's own budget, 40): a box that seems needed out after 20 draws is kept out, which at
worst makes the plan move one box more."""
REACH_SAMPLES: Final = 40
"""Points of a place tried before it is called out of the empty hand's reach."""
REACH_HEIGHT_M: Final = 0.10
"""How far above the place's face the pointing-down hand is asked to reach."""
AWAY_DEPTH_M: Final = 50.0
"""How far below the floor a box moved out of the scene is put (each its own spot)."""


@contextmanager
def moved_away(kitchen: KitchenScene, boxes: Iterable[str]) -> Iterator[None]:
    """The kitchen without ``boxes``: their bodies far below the floor (apart), and left out
    of the kitchen's boxes (so no check asks what they stand on); restored after."""
    everything = kitchen.boxes
    with kitchen.scene.preserved():
        away = list(boxes)
        for index, name in enumerate(away):
            kitchen.box(name).reset_base_pose(Pose((10.0 * (index + 1), 0.0, -AWAY_DEPTH_M)))
        kitchen.boxes = {name: body for name, body in everything.items() if name not in away}
        try:
            yield
        finally:
            kitchen.boxes = everything


def _finds_targets(
    kitchen: KitchenScene, action: GroundedAction, rng: np.random.Generator, parameters: SkillParameters
) -> bool:
    try:
        sample_action_targets(kitchen, action, rng, parameters)
    except SkillFailure:
        return False
    return True


def confirm_obstruction(
    kitchen: KitchenScene,
    action: GroundedAction,
    failure: SkillFailure,
    rng: np.random.Generator,
    parameters: SkillParameters = DEFAULT_PARAMETERS,
    keep: Collection[str] = (),
) -> tuple[str, ...]:
    """The boxes of ``failure.objects`` the action's skill needs out of the way (most blamed
    first), found as the module says; () when it finds no targets even with all of them out.
    The action's own arguments, and the boxes in ``keep``, are never blamed (they stay)."""
    put_back = replace(parameters, attempts=min(parameters.attempts, PUT_BACK_ATTEMPTS))
    out = [name for name in failure.objects
           if name not in action.args and name not in keep and name in kitchen.boxes]
    if not out:
        return ()
    with moved_away(kitchen, out):
        if not _finds_targets(kitchen, action, rng, parameters):
            return ()
    for name in reversed(list(out)):
        without = [other for other in out if other != name]
        with moved_away(kitchen, without):
            if _finds_targets(kitchen, action, rng, put_back):
                out = without
    return tuple(out)


def confirm_unreachable(
    kitchen: KitchenScene,
    action: GroundedAction,
    rng: np.random.Generator,
    place: str,
    parameters: SkillParameters = DEFAULT_PARAMETERS,
) -> bool:
    """Whether ``place`` is out of reach for ``action``: its skill still finds no targets with
    every box it does not name (and the hand does not hold) moved out of the scene, and the
    empty hand reaches no pose above the place (``hand_reaches_above``)."""
    held = kitchen.held_box()
    others = [name for name in kitchen.boxes if name not in action.args and name != held]
    with moved_away(kitchen, others):
        if _finds_targets(kitchen, action, rng, parameters):
            return False
    return not hand_reaches_above(kitchen, place)


def hand_reaches_above(kitchen: KitchenScene, place: str) -> bool:
    """Whether some pose of the hand pointing down, ``REACH_HEIGHT_M`` above a point of the
    place's face (``REACH_SAMPLES`` points, drawn from a fixed generator), has an IK solution
    within the joint ranges. The scene is left as it was."""
    region, rng = kitchen.region(place), np.random.default_rng(0)
    rotation, origin = region.world_from_region.rotation, region.world_from_region.translation
    with kitchen.scene.preserved():
        for _ in range(REACH_SAMPLES):
            x, y = rng.uniform(-1.0, 1.0, 2) * np.asarray(region.half_size)
            above = rotation @ np.array([x, y, REACH_HEIGHT_M]) + origin
            pose = Pose.from_rotation(above, WORLD_FROM_TOOL_DOWN)
            if kitchen.ik.solve(pose, rng, seeds=[kitchen.home, kitchen.arm_configuration()]) is not None:
                return True
    return False
