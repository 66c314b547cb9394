"""Build the kitchen scene for a problem: the robot on its mount, drawers opened or
closed, boxes laid out where ``:init`` puts them (``start_poses``) and the conditions it
names; Ψ of the result is checked against ``:init``."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path

import numpy as np

from kitchen_tamp.kitchen.abstraction import RESTING_GAP, check_initial_state
from kitchen_tamp.kitchen.conditions import conditions_among
from kitchen_tamp.kitchen.contact_policy import check_initial_overlaps
from kitchen_tamp.kitchen.errors import UnknownObjectError, UnsupportedInitialStateError
from kitchen_tamp.kitchen.scene.kitchen_map import (
    KITCHEN_BODY,
    ROBOT_BODY,
    ROBOT_MOUNT_LINK,
    KitchenMap,
    default_kitchen_map,
)
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.models import CABINET_LINK
from kitchen_tamp.kitchen.scene.regions import support_region
from kitchen_tamp.kitchen.scene.start_poses import (
    explicit_pose,
    exposed_floor,
    row_poses,
    start_supports,
    upright,
)
from kitchen_tamp.planning import Atom, Task, load_task
from kitchen_tamp.world import PANDA, Body, FloatArray, Pose, Robot, Scene, panda_urdf_path

HOME_HEIGHT_ABOVE_SURFACES = 0.30
"""The arm's home pose holds the tool this high above the surfaces, pointing down."""

WORLD_FROM_TOOL_DOWN = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])
"""Tool z pointing down, fingers closing along the world y axis."""


def check_objects(objects: Mapping[str, str], kitchen_map: KitchenMap) -> None:
    """Raise ``UnknownObjectError`` (naming the scene file) for an object the kitchen lacks or
    types differently (in the types of the kitchen map's binding)."""
    scene = kitchen_map.scene_path
    for name, type_name in sorted(objects.items()):
        if kitchen_map.type_of(name) is None:
            known = ", ".join(kitchen_map.object_names())
            raise UnknownObjectError(name, f"the kitchen of {scene} only has {known}")
        kitchen_type = kitchen_map.pddl_type_of(name)
        if kitchen_type != type_name:
            called = kitchen_type or f"{kitchen_map.type_of(name)} the domain has no type for"
            raise UnknownObjectError(
                name, f"it is a {called} in the kitchen of {scene}, the problem says {type_name}"
            )


def home_configuration(kitchen: KitchenScene) -> FloatArray:
    """An arm configuration with the tool above the surfaces' near edge, pointing down."""
    regions = [kitchen.surface_region(s) for s in kitchen.map.surfaces]
    centre = np.mean([r.world_from_region.translation for r in regions], axis=0)
    base = kitchen.robot.body.base_pose().translation
    target = np.array([(base[0] + centre[0]) / 2.0, base[1], centre[2] + HOME_HEIGHT_ABOVE_SURFACES])
    world_from_tool = Pose.from_rotation(target, WORLD_FROM_TOOL_DOWN)
    rng = np.random.default_rng(0)
    q = kitchen.ik.solve(world_from_tool, rng, seeds=[kitchen.robot.mid_configuration()])
    if q is None:
        raise UnsupportedInitialStateError("the arm cannot reach its home pose above the counter")
    return q


def lay_out_boxes(kitchen: KitchenScene, supports: Mapping[str, str]) -> None:
    """Put every box on the support ``supports`` names (a box's base before it): the scene's start
    if it gives one, else in rows; on a box, centred on its top face."""
    places = sorted({s for s in supports.values() if s not in supports})
    front = float(kitchen.kitchen.aabb(CABINET_LINK)[0][0])
    for place in places:
        names = [b for b in supports if supports[b] == place]
        region = kitchen.region(place)
        if place in kitchen.map.openables and kitchen.is_opened(place):
            region = exposed_floor(region, front, names)
        starts = {b: kitchen.map.boxes[b].start for b in names}
        loose = [b for b in names if starts[b] is None]
        sizes = [kitchen.box_size(b) for b in loose]
        poses = dict(zip(loose, row_poses(region, loose, sizes, RESTING_GAP), strict=True))
        for name, start in starts.items():
            if start is not None:
                poses[name] = explicit_pose(region, name, start, kitchen.box_size(name), RESTING_GAP)
        for name in names:
            _put(kitchen, kitchen.box(name), name, poses[name])
    for name, base in supports.items():
        if base in supports:
            top, start = kitchen.box_top(base), kitchen.map.boxes[name].start
            size = kitchen.box_size(name)
            if start is None:
                pose = upright(top, (0.0, 0.0), size, 0.0, RESTING_GAP)
            else:
                pose = explicit_pose(top, name, start, size, RESTING_GAP)
            _put(kitchen, kitchen.box(name), name, pose)


def _put(kitchen: KitchenScene, body: Body, name: str, pose: Pose) -> None:
    kitchen.scene.set_base_pose(body, pose)
    kitchen.settle(name)


def build_kitchen(
    objects: Mapping[str, str],
    init_atoms: Iterable[Atom],
    gui: bool = False,
    kitchen_map: KitchenMap | None = None,
    polyhedral_contacts: bool = False,
    visuals: bool = True,
) -> KitchenScene:
    """The kitchen laid out from ``:init``; Ψ(scene) is checked to equal ``init_atoms``.
    ``polyhedral_contacts``: for a ``PhysicsWorld``; ``visuals=False``: a kitchen nobody looks at
    (`Scene`).

    Raises ``UnknownObjectError`` for objects the kitchen lacks,
    ``UnsupportedInitialStateError`` for starts it cannot lay out and
    ``InitialStateMismatchError`` when the layout's abstraction differs from ``:init``.
    """
    init = frozenset(init_atoms)
    kitchen_map = kitchen_map if kitchen_map is not None else default_kitchen_map()
    check_objects(objects, kitchen_map)
    boxes = sorted(n for n in objects if kitchen_map.type_of(n) == "box")
    supports = start_supports(init, boxes, kitchen_map)
    opened_predicates = kitchen_map.binding.predicates_for("opened")
    scene = Scene(gui=gui, polyhedral_contacts=polyhedral_contacts, visuals=visuals)
    try:
        kitchen_body = scene.load_urdf(KITCHEN_BODY, kitchen_map.kitchen_urdf, fixed_base=True)
        mount = support_region(kitchen_body, ROBOT_MOUNT_LINK, ROBOT_MOUNT_LINK)
        panda = scene.load_urdf(ROBOT_BODY, panda_urdf_path(), mount.world_from_region, fixed_base=True)
        robot = Robot(scene, panda, PANDA)
        box_bodies = {
            b: scene.load_urdf(b, kitchen_map.boxes[b].urdf, Pose((0.0, 0.0, -1.0 - i)))
            for i, b in enumerate(boxes)
        }
        kitchen = KitchenScene(scene, robot, kitchen_body, box_bodies, np.zeros(robot.dof), kitchen_map)
        for openable in kitchen_map.openables:
            lower, upper = kitchen.opening_limits(openable)
            opened = openable in objects and any((p, openable) in init for p in opened_predicates)
            kitchen.set_opening(openable, upper if opened else lower)
        kitchen.home = home_configuration(kitchen)
        robot.set_configuration(kitchen.home)
        kitchen.set_gripper_open()
        lay_out_boxes(kitchen, supports)
        kitchen.conditions = conditions_among(kitchen_map.binding, init)
        check_initial_overlaps(kitchen)
        check_initial_state(kitchen, objects, init)
    except BaseException:
        scene.close()
        raise
    return kitchen


def build_kitchen_for_task(
    task: Task,
    gui: bool = False,
    kitchen_map: KitchenMap | None = None,
    polyhedral_contacts: bool = False,
    visuals: bool = True,
) -> KitchenScene:
    """The kitchen for a parsed problem (the default kitchen unless ``kitchen_map`` is given)."""
    return build_kitchen(task.objects, task.init_atoms, gui=gui, kitchen_map=kitchen_map,
                         polyhedral_contacts=polyhedral_contacts, visuals=visuals)


def load_kitchen_problem(
    problem: Path | str, gui: bool = False, kitchen_map: KitchenMap | None = None
) -> tuple[Task, KitchenScene]:
    """Parse a problem file (domain beside it) and build its kitchen."""
    task = load_task(problem)
    return task, build_kitchen_for_task(task, gui=gui, kitchen_map=kitchen_map)
