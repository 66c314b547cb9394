"""Build the kitchen scene for a problem: the robot on its mount, drawers opened or
closed and boxes laid out on the surfaces or in the drawer named by ``:init``."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path

import numpy as np

from kitchen_tamp.kitchen.abstraction import RESTING_GAP, check_initial_state
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
from kitchen_tamp.kitchen.scene.regions import SupportRegion, support_region
from kitchen_tamp.planning import Atom, Task, load_task
from kitchen_tamp.world import PANDA, FloatArray, Pose, Robot, Scene, panda_urdf_path

HOME_HEIGHT_ABOVE_SURFACES = 0.30
"""The arm's home pose holds the tool this high above the surfaces, pointing down."""

WORLD_FROM_TOOL_DOWN = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])
"""Tool z pointing down, fingers closing along the world y axis."""


def check_objects(objects: Mapping[str, str], kitchen_map: KitchenMap) -> None:
    """Raise ``UnknownObjectError`` (naming the scene file) for an object the kitchen lacks or
    types differently."""
    scene = kitchen_map.scene_path
    for name, type_name in sorted(objects.items()):
        kitchen_type = kitchen_map.type_of(name)
        if kitchen_type is None:
            known = ", ".join(kitchen_map.object_names())
            raise UnknownObjectError(name, f"the kitchen of {scene} only has {known}")
        if kitchen_type != type_name:
            raise UnknownObjectError(
                name, f"it is a {kitchen_type} in the kitchen of {scene}, the problem says {type_name}"
            )


def box_locations(
    init_atoms: Iterable[Atom], boxes: Iterable[str]
) -> dict[str, str]:
    """Box -> the surface or openable it starts on/in, checked to be exactly one place."""
    locations: dict[str, list[str]] = {box: [] for box in boxes}
    for atom in sorted(init_atoms):
        if atom[0] == "holding":
            raise UnsupportedInitialStateError(
                f"(holding {atom[1]}) in :init: the kitchen starts with an empty hand; "
                "put the box on a surface or in the drawer instead"
            )
        if atom[0] in ("boxOn", "boxIn") and atom[1] in locations:
            locations[atom[1]].append(atom[2])
    for box, places in locations.items():
        if len(places) != 1:
            where = "nowhere" if not places else " and ".join(places)
            raise UnsupportedInitialStateError(
                f"box {box!r} must start on exactly one surface or in one drawer, :init puts it {where}"
            )
    return {box: places[0] for box, places in locations.items()}


def slot_poses(
    region: SupportRegion, sizes: list[tuple[float, float, float]], gap: float = RESTING_GAP
) -> list[Pose]:
    """Upright box poses side by side along the region's longer side, centred."""
    hx, hy = region.half_size
    along = 0 if hx >= hy else 1
    length = 2.0 * (hx if along == 0 else hy)
    footprint = [s[along] for s in sizes]
    spacing = (length - sum(footprint)) / (len(sizes) + 1)
    if spacing <= 0.0 or any(s[1 - along] > 2.0 * (hy if along == 0 else hx) for s in sizes):
        raise UnsupportedInitialStateError(f"the boxes do not fit side by side in {region.name!r}")
    poses = []
    cursor = -length / 2.0
    for size, width in zip(sizes, footprint, strict=True):
        cursor += spacing + width / 2.0
        local = np.zeros(3)
        local[along] = cursor
        local[2] = size[2] / 2.0 + gap
        poses.append(region.world_from_region @ Pose.from_parts(local, (0.0, 0.0, 0.0, 1.0)))
        cursor += width / 2.0
    return poses


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


def build_kitchen(
    objects: Mapping[str, str],
    init_atoms: Iterable[Atom],
    gui: bool = False,
    kitchen_map: KitchenMap | None = None,
) -> KitchenScene:
    """The kitchen laid out from ``:init``; Ψ(scene) is checked to equal ``init_atoms``.

    Raises ``UnknownObjectError`` for objects the kitchen lacks,
    ``UnsupportedInitialStateError`` for starts it cannot lay out and
    ``InitialStateMismatchError`` when the layout's abstraction differs from ``:init``.
    """
    init = frozenset(init_atoms)
    kitchen_map = kitchen_map if kitchen_map is not None else default_kitchen_map()
    check_objects(objects, kitchen_map)
    boxes = sorted(n for n, t in objects.items() if t == "box")
    locations = box_locations(init, boxes)
    scene = Scene(gui=gui)
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
            opened = openable in objects and ("opened", openable) in init
            kitchen.set_opening(openable, upper if opened else lower)
        kitchen.home = home_configuration(kitchen)
        robot.set_configuration(kitchen.home)
        kitchen.set_gripper_open()
        for place in sorted(set(locations.values())):
            names = [b for b in boxes if locations[b] == place]
            poses = slot_poses(kitchen.region(place), [kitchen.box_size(b) for b in names])
            for name, pose in zip(names, poses, strict=True):
                scene.set_base_pose(box_bodies[name], pose)
                kitchen.settle(name)
        check_initial_overlaps(kitchen)
        check_initial_state(kitchen, objects, init)
    except BaseException:
        scene.close()
        raise
    return kitchen


def build_kitchen_for_task(
    task: Task, gui: bool = False, kitchen_map: KitchenMap | None = None
) -> KitchenScene:
    """The kitchen for a parsed problem (the default kitchen unless ``kitchen_map`` is given)."""
    return build_kitchen(task.objects, task.init_atoms, gui=gui, kitchen_map=kitchen_map)


def load_kitchen_problem(
    problem: Path | str, gui: bool = False, kitchen_map: KitchenMap | None = None
) -> tuple[Task, KitchenScene]:
    """Parse a problem file (domain beside it) and build its kitchen."""
    task = load_task(problem)
    return task, build_kitchen_for_task(task, gui=gui, kitchen_map=kitchen_map)
