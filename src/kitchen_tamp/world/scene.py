"""A PyBullet scene that owns one physics client, its bodies and their attachments."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

import pybullet as p

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.errors import SceneClosedError, UnknownNameError
from kitchen_tamp.world.transforms import IDENTITY, Pose


@dataclass(frozen=True)
class SceneState:
    """Every body's base pose, every movable joint's position, and the attachments."""

    base_poses: tuple[tuple[str, Pose], ...]
    joint_positions: tuple[tuple[str, tuple[str, ...], tuple[float, ...]], ...]
    attachments: tuple[Attachment, ...]


class Scene:
    """One physics client (DIRECT unless ``gui``), closed by ``close()`` or ``with``.

    The simulation is never stepped: bodies are placed kinematically, and every
    change of a joint goes through ``set_joint_positions`` so that attached bodies
    follow their parent links (a ``PhysicsWorld`` steps a scene of its own).

    With ``polyhedral_contacts``, every URDF is loaded with the faces PyBullet's
    polyhedral (separating-axis) contacts need; a ``PhysicsWorld`` whose settings ask for
    them then uses them. Planning and the kinematic judge never ask for them.

    Without ``visuals``, URDFs are loaded without their visual shapes (the Panda's visual meshes
    are three quarters of its loading time): a scene nobody looks at. Pictures, recordings and
    viewers need them, and refuse such a scene (`require_visuals`).
    """

    def __init__(self, gui: bool = False, polyhedral_contacts: bool = False, visuals: bool = True) -> None:
        if gui and not visuals:
            raise ValueError("a GUI scene shows its visual shapes: it cannot be loaded without them")
        self.client: int = p.connect(p.GUI if gui else p.DIRECT)
        if self.client < 0:
            raise SceneClosedError("could not connect to a PyBullet physics server")
        self.polyhedral_contacts = polyhedral_contacts
        self.visuals = visuals
        self._urdf_flags = p.URDF_USE_INERTIA_FROM_FILE
        if polyhedral_contacts:
            self._urdf_flags |= p.URDF_INITIALIZE_SAT_FEATURES
        if not visuals:
            self._urdf_flags |= p.URDF_IGNORE_VISUAL_SHAPES
        self._bodies: dict[str, Body] = {}
        self._urdf_paths: dict[str, Path] = {}
        self._attachments: dict[str, Attachment] = {}
        self._connected = True

    def require_visuals(self, purpose: str) -> None:
        """Raises ValueError when the scene was loaded without its visual shapes (``purpose``: what
        needed them)."""
        if not self.visuals:
            raise ValueError(f"{purpose} needs visual shapes, and this scene was loaded without them")

    # -- lifetime ---------------------------------------------------------------------------
    def close(self) -> None:
        """Disconnect the physics client (safe to call twice)."""
        if self._connected:
            self._connected = False
            p.disconnect(physicsClientId=self.client)

    def __enter__(self) -> Scene:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    @property
    def connected(self) -> bool:
        """Whether the physics client is still open."""
        return self._connected

    # -- bodies -----------------------------------------------------------------------------
    def load_urdf(
        self, name: str, path: Path | str, world_from_base: Pose = IDENTITY, fixed_base: bool = False
    ) -> Body:
        """Load a URDF as the body called ``name``."""
        if not self._connected:
            raise SceneClosedError("the scene is closed")
        if name in self._bodies:
            raise ValueError(f"the scene already has a body called {name!r}")
        uid = p.loadURDF(
            str(path),
            basePosition=world_from_base.position,
            baseOrientation=world_from_base.quaternion,
            useFixedBase=fixed_base,
            flags=self._urdf_flags,
            physicsClientId=self.client,
        )
        body = Body(self.client, uid, name)
        self._bodies[name] = body
        self._urdf_paths[name] = Path(path).resolve()
        return body

    @property
    def urdf_paths(self) -> dict[str, Path]:
        """Body name -> the URDF file it was loaded from (a copy)."""
        return dict(self._urdf_paths)

    def body(self, name: str) -> Body:
        """The body called ``name``."""
        try:
            return self._bodies[name]
        except KeyError:
            raise UnknownNameError(f"the scene has no body {name!r}") from None

    @property
    def bodies(self) -> tuple[Body, ...]:
        """All bodies in load order."""
        return tuple(self._bodies.values())

    # -- kinematic state ---------------------------------------------------------------------
    def set_joint_positions(self, body: Body, names: Sequence[str], values: Sequence[float]) -> None:
        """Teleport joints and move every body attached (directly or not) to ``body``."""
        body.reset_joint_positions(names, values)
        self.update_attachments()

    def set_base_pose(self, body: Body, world_from_base: Pose) -> None:
        """Teleport a body's base and move what is attached to it."""
        body.reset_base_pose(world_from_base)
        self.update_attachments()

    # -- attachments -------------------------------------------------------------------------
    def attach(self, child: Body, parent: Body, parent_link: str) -> Attachment:
        """Rigidly attach ``child`` to ``parent_link`` at their current relative pose."""
        parent.link_index(parent_link)
        if child is parent:
            raise ValueError(f"cannot attach {child.name!r} to itself")
        attachment = Attachment.from_current_poses(parent, parent_link, child)
        self._attachments[child.name] = attachment
        return attachment

    def detach(self, child: Body) -> None:
        """Let ``child`` stay where it is, no longer following any link."""
        self._attachments.pop(child.name, None)

    def attachment_of(self, child: Body) -> Attachment | None:
        """The attachment carrying ``child``, if any."""
        return self._attachments.get(child.name)

    @property
    def attachments(self) -> tuple[Attachment, ...]:
        """Current attachments, parents before their children."""
        return tuple(self._attachments.values())

    def update_attachments(self) -> None:
        """Move attached bodies to follow their parents (chains resolved in order)."""
        pending = list(self._attachments.values())
        for _ in range(len(pending)):
            children = {a.child.name for a in pending}
            ready = [a for a in pending if a.parent.name not in children]
            for attachment in ready:
                attachment.apply()
            pending = [a for a in pending if a not in ready]
            if not pending:
                return

    # -- save / restore ----------------------------------------------------------------------
    def save_state(self) -> SceneState:
        """A snapshot of poses, joint positions and attachments."""
        joints = []
        for body in self._bodies.values():
            names = tuple(j.name for j in body.joints if j.movable)
            if names:
                values = tuple(float(v) for v in body.joint_positions(names))
                joints.append((body.name, names, values))
        return SceneState(
            base_poses=tuple((b.name, b.base_pose()) for b in self._bodies.values()),
            joint_positions=tuple(joints),
            attachments=self.attachments,
        )

    def restore_state(self, state: SceneState) -> None:
        """Put every body back as it was when ``state`` was saved."""
        for name, pose in state.base_poses:
            self._bodies[name].reset_base_pose(pose)
        for name, joint_names, values in state.joint_positions:
            self._bodies[name].reset_joint_positions(joint_names, values)
        self._attachments = {a.child.name: a for a in state.attachments}
        self.update_attachments()

    @contextmanager
    def preserved(self) -> Iterator[SceneState]:
        """Context in which any change to the scene is undone on exit."""
        state = self.save_state()
        try:
            yield state
        finally:
            self.restore_state(state)
