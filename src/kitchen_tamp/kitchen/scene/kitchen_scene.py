"""The kitchen as a scene: the world objects behind every symbol, and state changes
(grasp, release, drawer opening) that keep attachments right."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable, Mapping
from types import TracebackType

import numpy as np

from kitchen_tamp.kitchen.scene.kitchen_map import KitchenMap, default_kitchen_map
from kitchen_tamp.kitchen.scene.regions import SupportRegion, box_corners, box_size, support_region, top_face
from kitchen_tamp.planning import Atom
from kitchen_tamp.world import (
    AllowedContact,
    Body,
    FloatArray,
    InverseKinematics,
    KeptClearance,
    Pose,
    PyBulletCollisionChecker,
    Robot,
    Scene,
    make_collision_checker,
)


class KitchenScene:
    """A built kitchen: scene, robot, kitchen body, loaded boxes and the map between them."""

    def __init__(
        self,
        scene: Scene,
        robot: Robot,
        kitchen: Body,
        boxes: Mapping[str, Body],
        home: FloatArray,
        kitchen_map: KitchenMap | None = None,
    ) -> None:
        self.scene = scene
        self.robot = robot
        self.kitchen = kitchen
        self.boxes = dict(boxes)
        self.home = home
        self.map = kitchen_map if kitchen_map is not None else default_kitchen_map()
        self.ik = InverseKinematics(robot)
        self.conditions: set[Atom] = set()
        """The atoms of states geometry does not show (``clean``, ``cooked``; see
        ``kitchen_tamp.kitchen.conditions``)."""

    # -- lifetime ---------------------------------------------------------------------------
    def close(self) -> None:
        """Disconnect the physics client."""
        self.scene.close()

    def __enter__(self) -> KitchenScene:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    # -- symbols -> geometry ---------------------------------------------------------------------
    def box(self, name: str) -> Body:
        """The body of box ``name``."""
        return self.boxes[name]

    def box_size(self, name: str) -> tuple[float, float, float]:
        """Size (x, y, z) of box ``name``."""
        return box_size(self.boxes[name])

    def surface_region(self, surface: str) -> SupportRegion:
        """Where boxes stand on ``surface`` (now)."""
        return support_region(self.kitchen, self.map.surfaces[surface].link, surface)

    def openable_region(self, openable: str) -> SupportRegion:
        """The floor of ``openable``'s tray where it is now, with its walls as ceiling."""
        symbol = self.map.openables[openable]
        return support_region(self.kitchen, symbol.floor_link, openable, ceiling_link=symbol.link)

    def region_region(self, region: str) -> SupportRegion:
        """The face of a region's slab (a plate, a sink) where boxes stand on it."""
        return support_region(self.kitchen, self.map.regions[region].link, region)

    def box_top(self, box: str) -> SupportRegion:
        """The face of ``box`` that points up (now), where another box may stand."""
        return top_face(self.boxes[box].base_pose(), self.box_size(box), box)

    def region(self, name: str) -> SupportRegion:
        """Where boxes stand on a surface, a region, an openable or a box."""
        if name in self.map.surfaces:
            return self.surface_region(name)
        if name in self.map.regions:
            return self.region_region(name)
        if name in self.boxes:
            return self.box_top(name)
        return self.openable_region(name)

    # -- drawers ---------------------------------------------------------------------------------
    def opening_limits(self, openable: str) -> tuple[float, float]:
        """(closed, fully open) joint values of ``openable``."""
        joint = self.kitchen.joint(self.map.openables[openable].joint)
        return joint.lower, joint.upper

    def opening(self, openable: str) -> float:
        """Current joint value of ``openable``."""
        return float(self.kitchen.joint_positions([self.map.openables[openable].joint])[0])

    def set_opening(self, openable: str, value: float) -> None:
        """Slide ``openable`` (boxes inside ride along)."""
        joint = self.map.openables[openable].joint
        self.scene.set_joint_positions(self.kitchen, [joint], [value])

    def is_opened(self, openable: str) -> bool:
        """Whether the joint is beyond the symbol's ``opened_fraction`` of its travel."""
        lower, upper = self.opening_limits(openable)
        fraction = self.map.openables[openable].opened_fraction
        return self.opening(openable) >= lower + fraction * (upper - lower)

    # -- holding -----------------------------------------------------------------------------------
    def held_box(self) -> str | None:
        """The box attached to the robot, if any."""
        for name, body in self.boxes.items():
            attachment = self.scene.attachment_of(body)
            if attachment is not None and attachment.parent is self.robot.body:
                return name
        return None

    def grasp(self, box: str) -> None:
        """Attach ``box`` to the hand at its current relative pose."""
        self.scene.attach(self.boxes[box], self.robot.body, self.robot.description.hand_link)

    def release(self, box: str) -> None:
        """Detach ``box`` from the hand; inside a tray it then rides with the tray."""
        body = self.boxes[box]
        self.scene.detach(body)
        self.settle(box)

    def settle(self, box: str) -> None:
        """Attach a loose box to the tray it rests in, if any, so it moves with the drawer."""
        body = self.boxes[box]
        world_from_box = body.base_pose()
        bottom = float(np.min(box_corners(world_from_box, self.box_size(box))[:, 2]))
        for name, symbol in self.map.openables.items():
            region = self.openable_region(name)
            if region.contains_xy(world_from_box.translation) and bottom < region.ceiling_z:
                self.scene.attach(body, self.kitchen, symbol.link)
                return

    def set_gripper_open(self) -> None:
        """Open the fingers fully."""
        self.robot.set_gripper_width(self.robot.max_gripper_width)

    # -- intended contact ------------------------------------------------------------------------------
    def finger_contact(self, box: str) -> AllowedContact:
        """The fingers touching ``box``: intended while they close on it or let go of it."""
        return AllowedContact(box, robot_links=self.robot.finger_links)

    def handle_contact(self, openable: str) -> AllowedContact:
        """The gripper touching ``openable``'s handle: intended while it grips and pulls."""
        handle = self.map.openables[openable].handle_link
        return AllowedContact(self.kitchen.name, handle, self.robot.gripper_links)

    # -- checking ------------------------------------------------------------------------------------
    def collision_checker(
        self, allowed: Iterable[AllowedContact] = (), margin: float = 0.0, kept: Iterable[KeptClearance] = ()
    ) -> PyBulletCollisionChecker:
        """A checker of the scene as it is now (held box attached, drawers where they are);
        with a ``margin`` (m), configurations closer than that to contact count as colliding,
        and the ``kept`` clearances hold besides. The fingers may touch the box they hold
        (down to the contact bound)."""
        held = self.held_box()
        intended = tuple(allowed) + (() if held is None else (self.finger_contact(held),))
        return make_collision_checker(self.scene, self.robot, intended, margin, kept)

    def clear_of_boxes(self, besides: Iterable[str], clearance: float) -> tuple[KeptClearance, ...]:
        """``clearance`` kept from every box but those named ``besides`` (the one the hand works
        on and what it stands on or goes onto)."""
        skipped = set(besides)
        return tuple(KeptClearance(name, clearance) for name in self.boxes if name not in skipped)

    def collision_free_ik(
        self,
        world_from_tool: Pose,
        checker: PyBulletCollisionChecker,
        rng: np.random.Generator,
        max_solutions: int,
        rejected: Callable[[FloatArray], None] | None = None,
    ) -> FloatArray | None:
        """The first of up to ``max_solutions`` IK solutions (seeded from the home and the
        current configuration, then random) that ``checker`` finds valid, or None; then
        ``rejected`` is called with the first solution ``checker`` refused, if there was one."""
        seeds = [self.home, self.arm_configuration()]
        first_refused = None
        for q in itertools.islice(self.ik.solutions(world_from_tool, rng, seeds), max_solutions):
            if checker.is_valid(q)[0]:
                return q
            if first_refused is None:
                first_refused = q
        if rejected is not None and first_refused is not None:
            rejected(first_refused)
        return None

    def arm_configuration(self) -> FloatArray:
        """Current arm configuration (a copy)."""
        return np.array(self.robot.configuration())
