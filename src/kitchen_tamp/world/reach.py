"""A sound test that a tool pose lies beyond the arm's reach, made before any IK is tried.

Two facts of a serial arm of revolute joints, read off the loaded model:

- *The shoulder.* Where the first joints' axes all pass through one point (the Panda's joints 1
  and 2 meet at ``panda_link2``'s origin), that point stays put whatever the configuration:
  turning a joint about an axis through a point leaves the point, and every later axis through
  it, where they were.
- *The wrist.* The last joint turns the tool about an axis fixed in the tool's frame, so the
  origin of the link before it (the wrist) lies, for a given tool pose, on a circle about that
  axis.

Between the shoulder and the wrist each revolute joint turns about its child link's origin, so
the origin advances by the joint origin's fixed offset: however the joints turn, the wrist is
no farther from the shoulder than the sum of those offsets (the triangle inequality; 0.79 m on
the Panda). A tool pose whose wrist circle stays farther from the shoulder than that, by more
than IK's tolerances could make up, has no IK solution. `ArmReach.beyond` says so; it never
rejects a pose IK could reach (`tests/world/test_reach.py` holds it to that on reachable poses
drawn at random), and it passes poses it cannot rule out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kitchen_tamp.world.robot import Robot
from kitchen_tamp.world.transforms import FloatArray, Pose

FIXED_TOLERANCE_M = 1e-7
"""How far a point may move, in the model's own forward kinematics, and still count as fixed."""


@dataclass(frozen=True)
class ArmReach:
    """The shoulder (in the robot's base frame), the wrist's circle (in the tool frame) and the
    reach between them; build with `arm_reach`."""

    base_from_shoulder: FloatArray
    """The shoulder point in the base link's frame."""
    circle_center: FloatArray
    circle_normal: FloatArray
    circle_radius: float
    """The wrist's circle in the tool frame, as the last joint turns."""
    reach_m: float
    """No configuration puts the wrist farther than this from the shoulder."""
    slack_m: float
    """What a tool pose accepted by IK's tolerances can add to the wrist's distance."""

    def wrist_distance(self, world_from_base: Pose, world_from_tool: Pose) -> float:
        """The least distance from the shoulder to the wrist's circle with the tool at
        ``world_from_tool`` (the whole circle: the last joint's limits only add to it)."""
        shoulder = world_from_base.apply(self.base_from_shoulder)
        center = world_from_tool.apply(self.circle_center)
        normal = world_from_tool.rotation @ self.circle_normal
        offset = shoulder - center
        along = float(offset @ normal)
        across = float(np.linalg.norm(offset - along * normal))
        return math.hypot(along, across - self.circle_radius)

    def beyond(self, world_from_base: Pose, world_from_tool: Pose) -> bool:
        """True only if no configuration puts the tool within IK's tolerances of the pose."""
        return self.wrist_distance(world_from_base, world_from_tool) > self.reach_m + self.slack_m


def arm_reach(robot: Robot, position_tolerance: float, orientation_tolerance: float) -> ArmReach | None:
    """The reach test of ``robot``'s arm for IK accepting a tool within ``position_tolerance``
    (m) and ``orientation_tolerance`` (rad) of its target, or None when the arm lacks a shoulder
    before its wrist, has a prismatic joint, or its model does not behave as the test assumes."""
    body, description = robot.body, robot.description
    joints = [body.joint(name) for name in description.arm_joints]
    if len(joints) < 3 or not all(joint.revolute for joint in joints):
        return None
    links = [body.link_name(joints[0].parent_index)] + [joint.child_link for joint in joints]
    reference = robot.mid_configuration()
    world_from_base = body.base_pose()

    def origin(q: FloatArray, link: str) -> FloatArray:
        return np.asarray(robot.forward_kinematics(q, link).position, dtype=float)

    def fixed_under(link: str, joint: int) -> bool:
        turned = [reference.copy(), reference.copy()]
        turned[0][joint] += 1.0
        turned[1][joint] -= 0.7
        home = origin(reference, link)
        return all(np.linalg.norm(origin(q, link) - home) <= FIXED_TOLERANCE_M for q in turned)

    # links[i] is the child of joint i - 1 (links[0] the first joint's parent); the shoulder is
    # the last of them that every arm joint before it leaves in place.
    shoulder = 0
    for i in range(1, len(links) - 1):
        if not all(fixed_under(links[i], j) for j in range(i)):
            break
        shoulder = i
    wrist = len(links) - 2  # the last joint's parent link
    if wrist <= shoulder:
        return None
    reach = sum(
        float(np.linalg.norm(origin(reference, links[i]) - origin(reference, links[i - 1])))
        for i in range(shoulder + 1, wrist + 1)
    )
    circle = _wrist_circle(robot, reference, links[wrist])
    if circle is None:
        return None
    center, normal, radius = circle
    farthest = float(np.linalg.norm(center)) + radius
    return ArmReach(
        base_from_shoulder=world_from_base.inverse().apply(origin(reference, links[shoulder])),
        circle_center=center,
        circle_normal=normal,
        circle_radius=radius,
        reach_m=reach,
        slack_m=position_tolerance + orientation_tolerance * farthest + 1e-6,
    )


def _wrist_circle(
    robot: Robot, reference: FloatArray, wrist_link: str
) -> tuple[FloatArray, FloatArray, float] | None:
    """(center, unit normal, radius) of the circle the wrist link's origin draws in the tool
    frame as the last joint turns, from three turns a third of a circle apart; None unless a
    fourth turn lands on it."""

    def wrist_in_tool(angle: float) -> FloatArray:
        q = reference.copy()
        q[-1] = angle
        world_from_tool = robot.forward_kinematics(q)
        wrist = robot.forward_kinematics(q, wrist_link).position
        return np.asarray(world_from_tool.inverse().apply(wrist), dtype=float)

    points = [wrist_in_tool(angle) for angle in (0.0, 2.0 * math.pi / 3.0, 4.0 * math.pi / 3.0)]
    center = np.mean(points, axis=0)
    radius = float(np.linalg.norm(points[0] - center))
    normal = np.cross(points[1] - points[0], points[2] - points[0])
    if radius < FIXED_TOLERANCE_M or np.linalg.norm(normal) == 0.0:
        normal, radius = np.array([0.0, 0.0, 1.0]), 0.0  # the wrist sits on the last axis
    else:
        normal = normal / np.linalg.norm(normal)
    check = wrist_in_tool(1.0) - center
    if abs(float(np.linalg.norm(check)) - radius) > 1e-6 or abs(float(check @ normal)) > 1e-6:
        return None
    return center, normal, radius
