"""Dynamics for a loaded scene: gravity, 240 Hz stepping, joint motors, friction.

``PhysicsWorld`` turns a kinematic ``Scene`` (bodies placed, nothing stepped)
into a simulated one. Friction and contact parameters are set here, where the
models are loaded for physics, rather than written into the URDFs: the arm's
joints are position-controlled with the efforts and velocities its URDF
states, the fingers press with a bounded force, and passive joints (a drawer's
slide) get a velocity motor with target 0 whose force bound acts as dry
joint friction. Nothing is welded: a body held by the fingers is held by
friction alone.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
import pybullet as p

from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray


@dataclass(frozen=True)
class ContactMaterial:
    """Friction of a body's links: Coulomb (lateral), torsional (spinning, metres), rolling."""

    lateral: float
    spinning: float = 0.0
    rolling: float = 0.0

    def __post_init__(self) -> None:
        if self.lateral < 0.0 or self.spinning < 0.0 or self.rolling < 0.0:
            raise ValueError(f"friction coefficients must be non-negative: {self}")


@dataclass(frozen=True)
class PhysicsSettings:
    """How the world is simulated. Lengths in metres, forces in newtons, times in seconds."""

    time_step: float = 1.0 / 240.0
    gravity: float = 9.81
    solver_iterations: int = 50
    box_material: ContactMaterial = ContactMaterial(lateral=0.8, spinning=0.02)
    """Boxes. The fingers keep the Panda URDF's friction (1.0, torsional 0.1)."""
    fixture_material: ContactMaterial = ContactMaterial(lateral=0.6, spinning=0.01)
    """Surfaces, drawer and handle."""
    grip_force: float = 20.0
    """Force bound (N) of each finger's motor: the grip force once the fingers are stopped by
    what they hold (the Panda URDF's finger effort)."""
    grip_squeeze: float = 0.01
    """How much narrower (m) than the planned width the fingers are commanded while they hold
    something, so that they press with ``grip_force`` instead of resting on it; while they
    hold nothing they are commanded the planned width itself."""
    finger_coupling_force: float = 50.0
    """Force bound (N) of the gear that makes the fingers move together (0: no gear)."""
    finger_contact_stiffness: float = 1e6
    finger_contact_damping: float = 5e3
    """The fingers' contact stiffness (N/m) and damping (N s/m). The Panda URDF's compliant
    3e4 N/m and 1e3 N s/m let a held box creep round the closing axis, about a degree per
    second under its own weight (6 degrees over one carry, 3 cm at the far end of the
    baguette); this stiffness holds it within half a degree."""
    contact_breaking_threshold: float = 0.001
    """Distance (m) at which PyBullet forgets a contact point. Its default, 2 cm, keeps stale
    points between the finger meshes and a box whose normals point the wrong way once the
    fingers open: the box then sticks to a finger (releases fail, or a box is dragged away)."""
    polyhedral_contacts: bool = True
    """Contacts between convex meshes by PyBullet's separating-axis test and face clipping
    (``enableSAT``; the scene must be loaded with ``Scene(polyhedral_contacts=True)``) instead
    of GJK/EPA. With GJK/EPA, the edge at a finger mesh's tip could get a contact normal
    pointing out of the box it pressed on: once the fingers opened, that contact pushed
    them shut with their whole motor force and the box left with the hand (2 of about 240
    benchmark runs). Costs about half as much physics time again."""
    passive_joint_friction: float = 5.0
    """Dry friction (N or N m) of joints nothing drives, e.g. a drawer's slide: without it
    a drawer creeps shut when a box is put in it."""
    position_gain: float = 0.3
    velocity_gain: float = 1.0

    def __post_init__(self) -> None:
        if self.time_step <= 0.0 or self.grip_force <= 0.0 or self.grip_squeeze < 0.0:
            raise ValueError(f"invalid physics settings: {self}")


DEFAULT_PHYSICS = PhysicsSettings()


@dataclass(frozen=True)
class RobotContact:
    """A contact point between one of the robot's links and a link of another body."""

    robot_link: str
    body: str
    link: str
    distance: float
    """Signed distance (m): negative when the shapes interpenetrate."""
    normal_force: float
    """Newtons."""


def _floats(values: FloatArray | Sequence[float]) -> list[float]:
    """``values`` as the list of Python floats the simulator takes (a list is taken as it is)."""
    return values if isinstance(values, list) else np.asarray(values, dtype=float).tolist()


class PhysicsWorld:
    """Steps ``scene`` with gravity; drives ``robot``'s arm and fingers by motors.

    ``fixtures`` are bodies with fixed bases (the kitchen); their movable joints
    are passive. ``loose`` are free bodies (boxes). Call ``command_arm`` and
    ``command_gripper`` to set motor targets, then ``step``.
    """

    def __init__(
        self,
        scene: Scene,
        robot: Robot,
        fixtures: Sequence[Body],
        loose: Sequence[Body],
        settings: PhysicsSettings = DEFAULT_PHYSICS,
    ) -> None:
        self.scene = scene
        self.robot = robot
        self.settings = settings
        self.client = scene.client
        self.time = 0.0
        if settings.polyhedral_contacts and not scene.polyhedral_contacts:
            raise ValueError("polyhedral contacts need a scene loaded with them: "
                             "Scene(polyhedral_contacts=True)")
        for body in loose:
            scene.detach(body)
        p.setGravity(0.0, 0.0, -settings.gravity, physicsClientId=self.client)
        p.setPhysicsEngineParameter(
            fixedTimeStep=settings.time_step,
            numSolverIterations=settings.solver_iterations,
            deterministicOverlappingPairs=1,
            contactBreakingThreshold=settings.contact_breaking_threshold,
            enableSAT=int(settings.polyhedral_contacts),
            physicsClientId=self.client,
        )
        arm = robot.body
        description = robot.description
        self._arm_indices = list(arm.joint_indices(description.arm_joints))
        self._finger_indices = list(arm.joint_indices(description.finger_joints))
        limits = [self._joint_limits(arm, i) for i in self._arm_indices]
        self.arm_efforts: FloatArray = np.array([effort for effort, _ in limits])
        self.arm_velocity_limits: FloatArray = np.array([velocity for _, velocity in limits])
        self.finger_velocity_limit = min(self._joint_limits(arm, i)[1] for i in self._finger_indices)
        # the motor arguments every tick repeats, as PyBullet takes them (lists of floats)
        count = len(self._arm_indices)
        self._arm_forces = self.arm_efforts.tolist()
        self._resting, self._position_gains, self._velocity_gains = (
            [0.0] * count, [settings.position_gain] * count, [settings.velocity_gain] * count
        )
        self._finger_forces = [settings.grip_force] * len(self._finger_indices)
        for body in fixtures:
            self._set_material(body, body.link_indices, settings.fixture_material)
            self._make_passive(body)
        self._ignore_anchored_pairs([arm, *fixtures])
        for body in loose:
            self._set_material(body, body.link_indices, settings.box_material)
        if settings.finger_coupling_force > 0.0:
            self._couple_fingers()
        for link in robot.finger_links:
            p.changeDynamics(
                arm.uid,
                arm.link_index(link),
                contactStiffness=settings.finger_contact_stiffness,
                contactDamping=settings.finger_contact_damping,
                physicsClientId=self.client,
            )
        self.command_arm(robot.configuration())
        self.command_gripper(robot.gripper_width())

    @staticmethod
    def _joint_limits(body: Body, index: int) -> tuple[float, float]:
        """(effort, velocity) limits of a joint as its URDF states them."""
        info = p.getJointInfo(body.uid, index, physicsClientId=body.client)
        return float(info[10]), float(info[11])

    def _set_material(self, body: Body, links: Iterable[int], material: ContactMaterial) -> None:
        for link in links:
            p.changeDynamics(
                body.uid,
                link,
                lateralFriction=material.lateral,
                spinningFriction=material.spinning,
                rollingFriction=material.rolling,
                physicsClientId=self.client,
            )

    def _ignore_anchored_pairs(self, anchored: Sequence[Body]) -> None:
        """No contacts between links of two fixed-base bodies that are both welded to the world
        (the robot's base on its mount): neither can move, so their contact could push nothing,
        yet PyBullet took it as a contact every tick (the Panda's base mesh against the mount's
        box, a polyhedral test of about 75 us, 40% of a tick's collision detection) and solved
        the kitchen and the arm as one island."""
        welded = [(body, body.welded_links()) for body in anchored]
        for first, (body, links) in enumerate(welded):
            for other, other_links in welded[first + 1:]:
                for link in links:
                    for other_link in other_links:
                        p.setCollisionFilterPair(
                            body.uid, other.uid, link, other_link, 0, physicsClientId=self.client
                        )

    def _couple_fingers(self) -> None:
        """Gear the fingers to open and close together, as the gripper's mechanism does: with two
        independent finger motors both pressing at their force bound, the fingers and the box
        between them slide freely along the closing axis whenever the hand accelerates."""
        uid = self.robot.body.uid
        first = self._finger_indices[0]
        for other in self._finger_indices[1:]:
            gear = p.createConstraint(
                uid, first, uid, other, p.JOINT_GEAR, [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0],
                physicsClientId=self.client,
            )
            p.changeConstraint(
                gear, gearRatio=-1.0, erp=0.1, maxForce=self.settings.finger_coupling_force,
                physicsClientId=self.client,
            )

    def _make_passive(self, body: Body) -> None:
        """Movable joints of a fixture resist motion with dry friction and nothing else."""
        for joint in body.joints:
            if joint.movable:
                p.setJointMotorControl2(
                    body.uid,
                    joint.index,
                    p.VELOCITY_CONTROL,
                    targetVelocity=0.0,
                    force=self.settings.passive_joint_friction,
                    physicsClientId=self.client,
                )

    # -- commands ---------------------------------------------------------------------------------
    def command_arm(
        self, q: FloatArray | Sequence[float], qd: FloatArray | Sequence[float] | None = None
    ) -> None:
        """Position targets (and feed-forward velocities) for the arm joints, bounded by the
        URDF efforts."""
        p.setJointMotorControlArray(
            self.robot.body.uid,
            self._arm_indices,
            p.POSITION_CONTROL,
            targetPositions=_floats(q),
            targetVelocities=self._resting if qd is None else _floats(qd),
            forces=self._arm_forces,
            positionGains=self._position_gains,
            velocityGains=self._velocity_gains,
            physicsClientId=self.client,
        )

    def command_gripper(self, planned_width: float, press: bool = False) -> None:
        """Fingers to ``planned_width`` apart, each finger's force bounded by ``grip_force``; with
        ``press`` (they hold something), ``grip_squeeze`` narrower, so that they press on it."""
        target = planned_width - self.settings.grip_squeeze if press else planned_width
        target = min(max(float(target), 0.0), self.robot.max_gripper_width)
        count = len(self._finger_indices)
        p.setJointMotorControlArray(
            self.robot.body.uid,
            self._finger_indices,
            p.POSITION_CONTROL,
            targetPositions=[target / count] * count,
            forces=self._finger_forces,
            physicsClientId=self.client,
        )

    # -- stepping and reading ---------------------------------------------------------------------
    def step(self, count: int = 1) -> None:
        """Advance the simulation by ``count`` time steps."""
        for _ in range(count):
            p.stepSimulation(physicsClientId=self.client)
        self.time += count * self.settings.time_step

    def arm_positions(self) -> list[float]:
        """Positions of the arm joints (read every tick: a list, not an array)."""
        states = p.getJointStates(self.robot.body.uid, self._arm_indices, physicsClientId=self.client)
        return [s[0] for s in states]

    def finger_speed(self) -> float:
        """Fastest finger joint speed (m/s)."""
        states = p.getJointStates(self.robot.body.uid, self._finger_indices, physicsClientId=self.client)
        return float(max(abs(s[1]) for s in states))

    def body_speed(self, body: Body) -> tuple[float, float]:
        """(linear m/s, angular rad/s) speed of a free body's base."""
        linear, angular = p.getBaseVelocity(body.uid, physicsClientId=self.client)
        return float(np.linalg.norm(linear)), float(np.linalg.norm(angular))

    def touching_links(self, body: Body, other: Body) -> frozenset[str]:
        """Names of ``other``'s links in contact with ``body`` after the last step."""
        contacts = p.getContactPoints(bodyA=body.uid, bodyB=other.uid, physicsClientId=self.client)
        return frozenset(other.link_name(c[4]) for c in contacts)

    def robot_contacts(self, min_force: float | None = None) -> list[RobotContact]:
        """Every contact point of the robot with another body after the last step (only those
        pressing harder than ``min_force`` newtons, if given)."""
        robot = self.robot.body
        contacts = p.getContactPoints(bodyA=robot.uid, physicsClientId=self.client)
        if min_force is not None:
            contacts = [contact for contact in contacts if contact[9] > min_force]
        if not contacts:
            return []
        names = {body.uid: body for body in self.scene.bodies}
        found = []
        for contact in contacts:
            other = names.get(contact[2])
            if other is None or other is robot:
                continue
            found.append(
                RobotContact(
                    robot.link_name(contact[3]), other.name, other.link_name(contact[4]),
                    float(contact[8]), float(contact[9]),
                )
            )
        return found

    def holds(self, body: Body) -> bool:
        """Whether every finger of the robot touches ``body``."""
        return self.robot.finger_links <= self.touching_links(body, self.robot.body)

