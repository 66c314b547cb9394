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
planned path (`PlanningCheckers.strict`), whose verdicts are then PyBullet's.

A refinement run asks for a model of every move, and many moves see the same
world (a skill resampled, a step tried again after backtracking, the arm
elsewhere but nothing else moved): `PlanningCheckers` builds each model once per
world and margin and hands out the same one again. The world is everything a
model reads of the scene description but the arm's joint positions (which every
query sets), so a reused model gives the verdicts a new one would. Drake's model
is built only when the spheres first defer to it (`DeferredDrakeChecker`), and with a
`DrakeService` (a planning run's) it is built and asked in the service's process,
which loaded Drake while the run started, so that the run itself never loads it.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from types import MappingProxyType
from typing import TYPE_CHECKING

import numpy as np

from kitchen_tamp.kitchen import KitchenScene, SkillTargets
from kitchen_tamp.motion.collision_checker import (
    CollisionChecker,
    JointConfiguration,
    JointConfigurations,
    ValidityMask,
)
from kitchen_tamp.refinement.motion_backend import BoundedCollisionChecker
from kitchen_tamp.world.scene_description import SceneDescription, describe_collision_checker

if TYPE_CHECKING:  # the real imports load Drake and numba, which a run may not need yet
    from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
    from kitchen_tamp.motion.geometry.drake_service import DrakeService, RemoteDrakeModel
    from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker

COLLISION_MODELS = MappingProxyType(
    {
        "spheres": "the sphere model's batched checks; Drake decides what they reject and measures distances",
        "drake": "Drake SceneGraph distance queries on the same URDFs (about 2x faster per check)",
        "pybullet": "PyBullet closest-point queries, as the verifier uses",
    }
)
"""Name -> description of the collision models planning can use."""
DEFAULT_COLLISION_MODEL = "spheres"


REMEMBERED_WORLDS = 16
"""Worlds (scene and margin) whose models a `PlanningCheckers` keeps, least recently used forgotten."""


def world_key(description: SceneDescription) -> bytes:
    """A digest of what a collision model reads of ``description``, the arm's joint positions
    excepted: two descriptions with one key give one model."""
    digest = hashlib.sha256()

    def add(*parts: object) -> None:
        for part in parts:
            if isinstance(part, np.ndarray):
                digest.update(np.ascontiguousarray(part, dtype=float).tobytes())
            else:
                digest.update(repr(part).encode())
            digest.update(b"|")

    arm = set(description.arm_joints)
    for body in description.bodies:
        held = sorted((name, value) for name, value in body.joint_positions.items()
                      if body.name != description.robot or name not in arm)
        add("body", body.name, body.urdf_path, body.base_link, body.world_from_base, held)
    for attachment in description.attachments:
        add("attached", attachment.parent, attachment.parent_link, attachment.child,
            attachment.parent_link_from_child)
    add("robot", description.robot, description.arm_joints, description.arm_lower, description.arm_upper,
        sorted(description.gripper_links))
    for pair in description.checked_pairs:
        add("pair", pair.body_a, pair.link_a, pair.body_b, pair.link_b, pair.allowance)
    return digest.digest()


class DeferredDrakeChecker:
    """Drake's model of a scene, built on the first question asked of it (the sphere model in
    front of it answers most moves alone); with a `DrakeService`, validity is asked of the
    service's model (the other questions, which only trajectory optimisation asks, of a model
    built here)."""

    def __init__(
        self, description: SceneDescription, margin: float, service: DrakeService | None = None
    ) -> None:
        self.margin = float(margin)
        self.lower: JointConfiguration = np.array(description.arm_lower, dtype=float)
        self.upper: JointConfiguration = np.array(description.arm_upper, dtype=float)
        self._description: SceneDescription = description
        self._model: DrakeCollisionChecker | None = None
        self._service = service
        self._remote: RemoteDrakeModel | None = None

    @property
    def built(self) -> bool:
        """Whether Drake's model has been built."""
        return self._model is not None

    @property
    def model(self) -> DrakeCollisionChecker:
        """Drake's model (built now if it was not)."""
        if self._model is None:
            from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker

            self._model = DrakeCollisionChecker(self._description, margin=self.margin)
        return self._model

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        if self._service is None or self._model is not None:
            return self.model.is_valid(qs)
        if self._remote is None:
            self._remote = self._service.model(self._description, self.margin)
        return self._remote.is_valid(qs)

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        return self.model.segment_valid(q0, q1)

    def min_distance(self, q: JointConfiguration) -> float:
        return self.model.min_distance(q)

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]:
        return self.model.signed_distance(q)


class PlanningCheckers:
    """The planning collision models of one refinement run, each built once per world and margin
    (see the module's docstring); ``model`` is a name of ``COLLISION_MODELS``."""

    def __init__(
        self, model: str = DEFAULT_COLLISION_MODEL, remembered: int = REMEMBERED_WORLDS,
        drake: DrakeService | None = None,
    ) -> None:
        if model not in COLLISION_MODELS:
            choices = ", ".join(COLLISION_MODELS)
            raise ValueError(f"unknown collision model {model!r}; choose one of {choices}")
        self.model = model
        self.remembered = remembered
        self.built = 0
        """Models built so far (a reused one is not counted again)."""
        self.drake = drake
        """Where Drake's models behind the spheres are asked (None: in this process)."""
        self._models: OrderedDict[tuple[bytes, float], BoundedCollisionChecker] = OrderedDict()

    def checker(self, kitchen: KitchenScene, targets: SkillTargets, margin: float) -> BoundedCollisionChecker:
        """A checker of the scene ``targets.free_space_checker`` captured, keeping ``margin``."""
        if self.model == "pybullet":
            with kitchen.scene.preserved():
                kitchen.robot.set_gripper_width(targets.gripper_width)
                return kitchen.collision_checker(margin=margin)
        description = describe_collision_checker(targets.free_space_checker)
        key = (world_key(description), float(margin))
        known = self._models.get(key)
        if known is not None:
            self._models.move_to_end(key)
            return known
        built = self._build(description, margin)
        self.built += 1
        self._models[key] = built
        if len(self._models) > self.remembered:
            self._models.popitem(last=False)
        return built

    def strict(self, targets: SkillTargets, planning: BoundedCollisionChecker) -> CollisionChecker:
        """What a path planned with ``planning`` (one of this object's checkers) must be free
        under: the skill's PyBullet checker, screened by the planning checker's spheres (at the
        PyBullet checker's margin) when it plans with spheres, so that only configurations the
        spheres reject are asked of PyBullet. Verdicts are PyBullet's."""
        exact = targets.free_space_checker
        if self.model != "spheres":
            return exact
        from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker

        if not isinstance(planning, SphereScreenedChecker):
            raise TypeError(f"a sphere model's checker expected, got {type(planning).__name__}")
        return SphereScreenedChecker(planning.spheres.with_margin(exact.margin), exact)

    def _build(self, description: SceneDescription, margin: float) -> BoundedCollisionChecker:
        if self.model == "drake":
            return DeferredDrakeChecker(description, margin).model
        # imported here: numba loads only when the sphere model is used
        from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
        from kitchen_tamp.motion.geometry.spheres.screening import SphereScreenedChecker

        spheres: SphereCollisionChecker = SphereCollisionChecker(description, margin=margin)
        exact = DeferredDrakeChecker(description, margin, self.drake)
        return SphereScreenedChecker(spheres, exact, exact_is_bare=True)
