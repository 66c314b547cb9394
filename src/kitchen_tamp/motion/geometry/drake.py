"""A Drake collision model of a scene snapshot: a `CollisionChecker` with signed distances.

Built once from a scene description (`kitchen_tamp.world.scene_description`,
read here through the `DescribedScene` protocol so that motion never imports
the PyBullet side): a MultibodyPlant + SceneGraph with every body parsed from
its URDF, bases welded to the world where they stand, attached bodies welded to
their parent link (a carried box follows the hand), and every joint but the
arm's held where the description has it (the drawer, the fingers). Only the
arm's joints change between queries.

Collision filters leave exactly the pairs the description lists
(``checked_pairs``: the pair policy that ``kitchen_tamp.world.collision.checked_pairs``
decides for every collision model, read here as plain names), and a pair listed
with an allowance (an intended contact) collides only when it penetrates deeper
than that (a margin does not apply to it).

How answers differ from PyBullet's. Both collide the Panda's .obj meshes as
their convex hulls (Drake for a `Mesh` in point-contact and signed-distance
queries, PyBullet for every mesh a URDF loads) and boxes exactly. PyBullet
pads each convex mesh with its ~1 mm collision margin, so its distances are
about 1 mm smaller per mesh in the pair (2 mm between two Panda links, 1 mm
between a link and a box) and Drake is that much more permissive: on random
kitchen configurations ~1% are colliding for PyBullet and free for Drake, all
within 2 mm of contact, none the other way round; with ``margin=0.002`` Drake
agrees on >99.9% and, in our samples, never accepts what PyBullet rejects.
Drake's signed distance is exact for the hulls, penetration included, with
witness points on both shapes from which `signed_distance` takes its gradient.
"""

from __future__ import annotations

import itertools
import logging
import re
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from pydrake.geometry import CollisionFilterDeclaration, GeometrySet, SceneGraph
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, MultibodyPlant
from pydrake.multibody.tree import BodyIndex, JacobianWrtVariable, ModelInstanceIndex
from pydrake.systems.framework import DiagramBuilder

from kitchen_tamp.joint_spacing import PLANNING_RESOLUTION_RAD
from kitchen_tamp.motion.collision_checker import JointConfiguration, JointConfigurations, ValidityMask
from kitchen_tamp.motion.geometry.described_scene import (
    DEFAULT_DISTANCE_HORIZON,
    DescribedBody,
    DescribedScene,
)
from kitchen_tamp.motion.segment_checking import CountingSegmentChecker

FloatArray = npt.NDArray[np.float64]



@contextmanager
def _quiet_drake_parser() -> Iterator[None]:
    """Silence Drake's warnings about URDF tags it ignores (safety_controller, massless links)."""
    logger = logging.getLogger("drake")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


def _rigid_transform(matrix: FloatArray) -> RigidTransform:
    """A 4x4 homogeneous matrix as Drake's transform (stubs misspell the array type)."""
    return RigidTransform(np.asarray(matrix, dtype=float))  # type: ignore[arg-type]


def _add_model(plant: MultibodyPlant, body: DescribedBody) -> ModelInstanceIndex:
    """Parse a body's URDF; ``package://NAME/...`` resolves beside the URDF, as in PyBullet."""
    path = Path(body.urdf_path)
    parser = Parser(plant, body.name)
    for package in sorted(set(re.findall(r"package://([^/\"']+)/", path.read_text()))):
        if (path.parent / package).is_dir():
            parser.package_map().Add(package, path.parent / package)
    (instance,) = parser.AddModels(path)
    return instance


class DrakeCollisionChecker:
    """Batch validity, minimum distance and signed distance (with gradient) of arm configurations.

    A configuration is valid within the arm's limits when no checked pair is
    closer than ``margin`` (m); distances are measured up to ``distance_horizon``;
    ``segment_valid`` checks straight segments every ``segment_resolution``
    (Euclidean joint-space distance, rad).
    """

    def __init__(
        self,
        scene: DescribedScene,
        margin: float = 0.0,
        distance_horizon: float = DEFAULT_DISTANCE_HORIZON,
        segment_resolution: float = PLANNING_RESOLUTION_RAD,
    ) -> None:
        self.margin = float(margin)
        self.distance_horizon = float(distance_horizon)
        self.lower: FloatArray = np.array(scene.arm_lower, dtype=float)
        self.upper: FloatArray = np.array(scene.arm_upper, dtype=float)
        builder = DiagramBuilder()
        # Typed Any: pydrake's stubs spell arrays ndarray[float64, ...], which numpy's
        # generic ndarray[shape, dtype] rejects for every float array.
        plant: Any
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        self.plant = plant
        with _quiet_drake_parser():
            self._instances = {body.name: _add_model(plant, body) for body in scene.bodies}
        self._weld(scene)
        plant.Finalize()
        self._allowances: dict[tuple[Any, Any], float] = {}
        """(geometry, geometry) -> depth (m) the pair may penetrate, both orders, intended contacts only."""
        self.contact_pairs: dict[frozenset[str], float] = {}
        """Pairs (as ``model/link`` names) that may touch down to the given depth (m)."""
        self.checked_pairs = self._filter_unchecked_pairs(scene, scene_graph)
        """Pairs of bodies with collision geometry (as ``model/link`` names) that are checked."""
        self._diagram = builder.Build()
        self._diagram_context = self._diagram.CreateDefaultContext()
        self._context = plant.GetMyMutableContextFromRoot(self._diagram_context)
        self._positions = self._described_positions(scene)
        robot = self._instances[scene.robot]
        self._arm_slots = np.array(
            [plant.GetJointByName(n, robot).position_start() for n in scene.arm_joints]
        )
        self._query_port = plant.get_geometry_query_input_port()
        inspector = scene_graph.model_inspector()
        self._geometry_bodies: dict[Any, tuple[Any, RigidTransform]] = {
            geometry: (
                plant.GetBodyFromFrameId(inspector.GetFrameId(geometry)),
                inspector.GetPoseInFrame(geometry),
            )
            for geometry in inspector.GetAllGeometryIds()
        }
        self._segments = CountingSegmentChecker(self, segment_resolution)

    # -- building ------------------------------------------------------------------------------------
    def _weld(self, scene: DescribedScene) -> None:
        """Attached bodies to their parent link, every other base link to the world where it stands."""
        plant, instances = self.plant, self._instances
        attached = {a.child for a in scene.attachments}
        for attachment in scene.attachments:
            child = next(b for b in scene.bodies if b.name == attachment.child)
            plant.WeldFrames(
                plant.GetFrameByName(attachment.parent_link, instances[attachment.parent]),
                plant.GetFrameByName(child.base_link, instances[child.name]),
                _rigid_transform(attachment.parent_link_from_child),
            )
        for body in scene.bodies:
            if body.name not in attached:
                plant.WeldFrames(
                    plant.world_frame(),
                    plant.GetFrameByName(body.base_link, instances[body.name]),
                    _rigid_transform(body.world_from_base),
                )

    def _described_positions(self, scene: DescribedScene) -> FloatArray:
        positions = np.array(self.plant.GetPositions(self._context), dtype=float)
        for body in scene.bodies:
            for name, value in body.joint_positions.items():
                joint = self.plant.GetJointByName(name, self._instances[body.name])
                positions[joint.position_start()] = value
        return positions

    def _scoped(self, body: BodyIndex) -> str:
        return f"{self._model_of(body)}/{self.plant.get_body(body).name()}"

    def _model_of(self, body: BodyIndex) -> str:
        instance = self.plant.get_body(body).model_instance()
        return next(name for name, index in self._instances.items() if index == instance)

    def _checked_pairs(self, scene: DescribedScene) -> dict[frozenset[BodyIndex], float]:
        """The described pairs as Drake bodies, each with its allowance (m)."""
        plant, instances = self.plant, self._instances
        checked: dict[frozenset[BodyIndex], float] = {}
        for pair in scene.checked_pairs:
            if pair.allowance < 0.0:
                raise ValueError(
                    f"{pair.body_a}/{pair.link_a} keeps a clearance from {pair.body_b}/{pair.link_b}, "
                    "which Drake's model does not check"
                )
            a = plant.GetBodyByName(pair.link_a, instances[pair.body_a]).index()
            b = plant.GetBodyByName(pair.link_b, instances[pair.body_b]).index()
            key = frozenset((a, b))
            checked[key] = max(checked.get(key, 0.0), float(pair.allowance))
        return checked

    def _filter_unchecked_pairs(
        self, scene: DescribedScene, scene_graph: SceneGraph
    ) -> frozenset[frozenset[str]]:
        """Exclude every pair of bodies with geometry that is not checked; the checked ones by name."""
        plant = self.plant
        checked = self._checked_pairs(scene)
        shaped = [
            (BodyIndex(i), plant.GetCollisionGeometriesForBody(plant.get_body(BodyIndex(i))))
            for i in range(plant.num_bodies())
        ]
        shaped = [(body, geometries) for body, geometries in shaped if geometries]
        declaration = CollisionFilterDeclaration()
        kept = []
        for (a, geometries_a), (b, geometries_b) in itertools.combinations(shaped, 2):
            key = frozenset((a, b))
            if key not in checked:
                declaration.ExcludeBetween(GeometrySet(geometries_a), GeometrySet(geometries_b))
            else:
                kept.append(frozenset((self._scoped(a), self._scoped(b))))
                if checked[key] > 0.0:
                    self.contact_pairs[kept[-1]] = checked[key]
                    for first, second in itertools.product(geometries_a, geometries_b):
                        self._allowances[first, second] = self._allowances[second, first] = checked[key]
        scene_graph.collision_filter_manager().Apply(declaration)
        return frozenset(kept)

    # -- queries ---------------------------------------------------------------------------------------
    def _query_at(self, q: JointConfiguration) -> Any:
        """SceneGraph's query object with the arm at ``q``."""
        self._positions[self._arm_slots] = q
        self.plant.SetPositions(self._context, self._positions)
        return self._query_port.Eval(self._context)

    def _allowance(self, pair: Any) -> float:
        """The depth (m) a pair of geometries (a distance or penetration result) may penetrate."""
        return self._allowances.get((pair.id_A, pair.id_B), 0.0) if self._allowances else 0.0

    def _collides(self, q: JointConfiguration) -> bool:
        query = self._query_at(q)
        # an intended contact may touch to its allowance, whatever the margin
        if self._allowances and self.margin > 0.0:
            pairs = query.ComputeSignedDistancePairwiseClosestPoints(self.margin)
            return any(
                pair.distance < (-allowance if (allowance := self._allowance(pair)) > 0.0 else self.margin)
                for pair in pairs
            )
        if self._allowances:
            return any(
                pair.depth > (allowance if (allowance := self._allowance(pair)) > 0.0 else -self.margin)
                for pair in query.ComputePointPairPenetration()
            )
        if self.margin > 0.0:
            pairs = query.ComputeSignedDistancePairwiseClosestPoints(self.margin)
            return any(pair.distance < self.margin for pair in pairs)
        if self.margin == 0.0:
            return bool(query.HasCollisions())
        return any(pair.depth > -self.margin for pair in query.ComputePointPairPenetration())

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        """Per row of ``qs`` (n, 7): within the arm's limits and no checked pair closer than the margin."""
        batch = np.atleast_2d(np.asarray(qs, dtype=float))
        valid = np.all((batch >= self.lower - 1e-9) & (batch <= self.upper + 1e-9), axis=1)
        for i in np.flatnonzero(valid).tolist():
            valid[i] = not self._collides(batch[i])
        return np.asarray(valid, dtype=np.bool_)

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        """Whether the straight segment is valid, checked at the checker's resolution."""
        return self._segments.segment_valid(np.asarray(q0, dtype=float), np.asarray(q1, dtype=float))

    def _closest_pair(self, q: JointConfiguration) -> tuple[Any, float] | None:
        """The pair nearest to colliding and its distance plus allowance, or None."""
        pairs = self._query_at(q).ComputeSignedDistancePairwiseClosestPoints(self.distance_horizon)
        measured = [(pair, float(pair.distance), self._allowance(pair)) for pair in pairs]
        # an intended contact counts only when deeper than allowed, from its allowed depth
        counted = [(pair, d + a) for pair, d, a in measured if a == 0.0 or d + a < 0.0]
        return min(counted, key=lambda item: item[1], default=None)

    def min_distance(self, q: JointConfiguration) -> float:
        """Smallest signed distance (m, negative when penetrating; an intended contact counted
        only when deeper than allowed, from its allowed depth) over the checked pairs, capped
        at ``distance_horizon``."""
        closest = self._closest_pair(np.asarray(q, dtype=float))
        return self.distance_horizon if closest is None else min(closest[1], self.distance_horizon)

    def signed_distance(self, q: JointConfiguration) -> tuple[float, JointConfiguration]:
        """(``min_distance(q)``, its gradient with respect to the arm joints); the gradient is
        zero beyond the horizon. A `SignedDistanceFunction` for trajectory optimisation."""
        closest = self._closest_pair(np.asarray(q, dtype=float))
        if closest is None or closest[1] >= self.distance_horizon:
            return self.distance_horizon, np.zeros(len(self._arm_slots))
        pair, distance = closest
        velocity_of = self._witness_jacobian
        jacobian = velocity_of(pair.id_A, pair.p_ACa) - velocity_of(pair.id_B, pair.p_BCb)
        gradient = np.asarray(pair.nhat_BA_W, dtype=float) @ jacobian[:, self._arm_slots]
        return distance, np.asarray(gradient, dtype=float)

    def _witness_jacobian(self, geometry: Any, p_GC: FloatArray) -> FloatArray:
        """(3, nq) velocity Jacobian of a witness point fixed on a geometry's body."""
        body, body_from_geometry = self._geometry_bodies[geometry]
        world = self.plant.world_frame()
        return np.asarray(
            self.plant.CalcJacobianTranslationalVelocity(
                self._context,
                JacobianWrtVariable.kQDot,
                body.body_frame(),
                body_from_geometry @ p_GC,
                world,
                world,
            )
        )
