"""The collision model free-space moves are planned with: spheres (fastest), Drake's or PyBullet's.

All check the scene a skill's free-space checker captured (what the hand
carries, where the drawer is) and keep ``margin`` metres of clearance. PyBullet
stays the simulator and the verifier whichever is chosen: every planned path is
re-checked with the skill's own PyBullet checker before it is accepted.

``spheres`` is the conservative sphere model (`kitchen_tamp.motion.geometry.spheres.checker`)
in front of Drake's (`kitchen_tamp.motion.geometry.spheres.screening`): what the spheres
find free is free (they cover the links), what they reject Drake decides, so
verdicts are Drake's and most configurations never reach Drake. The same
spheres, at the PyBullet checker's margin, screen the dense post-check of the
planned path (`strict_checker`), whose verdicts are then PyBullet's.
"""

from __future__ import annotations

from types import MappingProxyType

from kitchen_tamp.kitchen import KitchenScene, SkillTargets
from kitchen_tamp.motion.collision_checker import CollisionChecker
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker
from kitchen_tamp.refinement.motion_backend import BoundedCollisionChecker
from kitchen_tamp.world.scene_description import describe_collision_checker

COLLISION_MODELS = MappingProxyType(
    {
        "spheres": "the sphere model's batched checks; Drake decides what they reject and measures distances",
        "drake": "Drake SceneGraph distance queries on the same URDFs (about 2x faster per check)",
        "pybullet": "PyBullet closest-point queries, as the verifier uses",
    }
)
"""Name -> description of the collision models planning can use."""
DEFAULT_COLLISION_MODEL = "spheres"


def planning_checker(
    kitchen: KitchenScene, targets: SkillTargets, margin: float, model: str = DEFAULT_COLLISION_MODEL
) -> BoundedCollisionChecker:
    """A checker of the scene ``targets.free_space_checker`` captured, keeping ``margin``."""
    if model in ("drake", "spheres"):
        description = describe_collision_checker(targets.free_space_checker)
        drake = DrakeCollisionChecker(description, margin=margin)
        if model == "drake":
            return drake
        # imported here: numba loads only when the sphere model is used
        from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker

        spheres = SphereCollisionChecker(description, margin=margin)
        return SphereScreenedChecker(spheres, drake, exact_is_bare=True)
    if model == "pybullet":
        with kitchen.scene.preserved():
            kitchen.robot.set_gripper_width(targets.gripper_width)
            return kitchen.collision_checker(margin=margin)
    raise ValueError(f"unknown collision model {model!r}; choose one of {', '.join(COLLISION_MODELS)}")


def strict_checker(targets: SkillTargets, planning: BoundedCollisionChecker) -> CollisionChecker:
    """What a planned path must be free under: the skill's PyBullet checker, screened by the
    planning checker's spheres (at the PyBullet checker's margin) when it plans with spheres,
    so that only configurations the spheres reject are asked of PyBullet. Verdicts are PyBullet's."""
    exact = targets.free_space_checker
    if isinstance(planning, SphereScreenedChecker):
        return SphereScreenedChecker(planning.spheres.with_margin(exact.margin), exact)
    return exact
