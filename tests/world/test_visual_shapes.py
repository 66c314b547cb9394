"""What bodies look like comes from their URDFs, and link frames read in one call agree with
``link_pose``."""

from __future__ import annotations

import numpy as np

from kitchen_tamp.world import Pose, Robot, Scene, VisualKind, visual_shapes


def test_visuals_are_the_urdfs_primitives_meshes_and_colours(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    kitchen = visual_shapes(scene.body("kitchen"))
    burners = [v for v in kitchen if v.kind is VisualKind.CYLINDER]
    assert len(burners) == 4 and all(v.link == "stove" for v in burners)
    assert {round(v.size[1], 3) for v in burners} == {0.05, 0.035}  # (length, radius): the radii
    slab = next(v for v in kitchen if v.kind is VisualKind.BOX and v.size == (0.6, 1.3, 0.04))
    assert slab.link == "cabinet" and np.allclose(slab.rgba, (0.55, 0.55, 0.58, 1.0), atol=1e-6)
    panda = visual_shapes(robot.body)
    meshes = {v.link: v.mesh_path for v in panda if v.kind is VisualKind.MESH}
    assert meshes["panda_hand"] is not None and meshes["panda_hand"].endswith("visual/hand.obj")
    fingers = [v for v in panda if v.link in ("panda_leftfinger", "panda_rightfinger")]
    assert len(fingers) == 2
    assert fingers[0].link_from_visual.distance_to(fingers[1].link_from_visual)[1] > 3.0  # turned round


def test_link_frames_agree_with_link_pose(panda_scene: tuple[Scene, Robot]) -> None:
    scene, robot = panda_scene
    robot.set_configuration(robot.lower + 0.3 * (robot.upper - robot.lower))
    box = scene.body("sugar")
    box.reset_base_pose(Pose((0.4, -0.1, 0.9), (0.0, 0.0, np.sin(0.3), np.cos(0.3))))
    for body in scene.bodies:
        positions, quaternions = body.link_frames(body.link_names)
        for link, position, quaternion in zip(body.link_names, positions, quaternions, strict=True):
            error = body.link_pose(link).distance_to(Pose.from_parts(position, quaternion))
            assert error[0] < 1e-6 and error[1] < 1e-5, (body.name, link)
