"""The simulated world: the only package that talks to PyBullet.

A ``Scene`` owns one physics client and its bodies (looked up by name); a
``Robot`` gives an arm's configuration, gripper and forward kinematics;
``InverseKinematics`` solves for tool poses with seeded restarts; a
``PyBulletCollisionChecker`` answers batch validity queries for motion planners;
``render`` takes headless pictures; ``visual_shapes`` says what a body looks like;
``physics.PhysicsWorld`` steps a scene with gravity, joint motors and friction for
execution under physics.
"""

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import BASE_LINK, Body, BoxShape, JointInfo
from kitchen_tamp.world.camera import (
    CameraView,
    Image,
    LinkVisibility,
    PixelWindow,
    StandIns,
    pixel_window,
    render,
    render_with_depth,
    tile,
    write_png,
)
from kitchen_tamp.world.collision.checker import (
    AllowedContact,
    BoolArray,
    KeptClearance,
    PyBulletCollisionChecker,
    make_collision_checker,
)
from kitchen_tamp.world.errors import SceneClosedError, UnknownNameError, WorldError
from kitchen_tamp.world.kinematics import IkOptions, InverseKinematics, straight_line
from kitchen_tamp.world.robot import PANDA, ArmDescription, Robot
from kitchen_tamp.world.scene import Scene, SceneState
from kitchen_tamp.world.scene_description import (
    AttachmentDescription,
    BodyDescription,
    SceneDescription,
    describe_collision_checker,
    describe_scene,
)
from kitchen_tamp.world.transforms import FloatArray, Pose, VectorLike, rotation_about_axis
from kitchen_tamp.world.visual_shapes import VisualKind, VisualShape, visual_shapes

__all__ = [
    "BASE_LINK",
    "PANDA",
    "AllowedContact",
    "ArmDescription",
    "Attachment",
    "AttachmentDescription",
    "Body",
    "BodyDescription",
    "BoolArray",
    "BoxShape",
    "CameraView",
    "FloatArray",
    "IkOptions",
    "Image",
    "InverseKinematics",
    "JointInfo",
    "KeptClearance",
    "LinkVisibility",
    "PixelWindow",
    "Pose",
    "PyBulletCollisionChecker",
    "Robot",
    "Scene",
    "SceneClosedError",
    "SceneDescription",
    "SceneState",
    "StandIns",
    "UnknownNameError",
    "VectorLike",
    "VisualKind",
    "VisualShape",
    "WorldError",
    "describe_collision_checker",
    "describe_scene",
    "make_collision_checker",
    "panda_urdf_path",
    "pixel_window",
    "render",
    "render_with_depth",
    "rotation_about_axis",
    "straight_line",
    "tile",
    "visual_shapes",
    "write_png",
]


def panda_urdf_path() -> str:
    """Path of the Franka Panda URDF shipped with ``pybullet_data``."""
    import pybullet_data

    return f"{pybullet_data.getDataPath()}/franka_panda/panda.urdf"
