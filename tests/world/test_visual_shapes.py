"""What bodies look like comes from their URDFs, and link frames read in one call agree with
``link_pose``; a scene loaded without its visuals collides alike and cannot be looked at."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.execute.render.scene_recording import SceneRecorder
from kitchen_tamp.world import CameraView, Pose, Robot, Scene, VisualKind, render, visual_shapes


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


def test_a_scene_without_visuals_collides_alike_and_refuses_to_be_looked_at(
    panda_scene: tuple[Scene, Robot],
) -> None:
    scene, robot = panda_scene
    with Scene(visuals=False) as bare:
        for body in scene.bodies:
            copy = bare.load_urdf(body.name, scene.urdf_paths[body.name], body.base_pose(), fixed_base=True)
            meshes = [v.mesh_path for v in visual_shapes(copy) if v.mesh_path is not None]
            assert not any("/visual/" in m for m in meshes)  # PyBullet shows the collision shapes
            movable = [j.name for j in body.joints if j.movable]
            if movable:
                copy.reset_joint_positions(movable, body.joint_positions(movable))
            for link in body.link_names:  # the same collision shapes, where they are
                assert np.array_equal(copy.aabb(link), body.aabb(link)), (body.name, link)
        assert visual_shapes(robot.body)  # the scene with visuals still has them
        with pytest.raises(ValueError, match="loaded without them"):
            render(bare, CameraView((0.0, 0.0, 1.0), 2.0, 0.0, -30.0))
        with pytest.raises(ValueError, match="loaded without them"):
            SceneRecorder(bare)
    with pytest.raises(ValueError, match="GUI"):
        Scene(gui=True, visuals=False)
