"""A carried body moved with its parent link in raw PyBullet transforms (the collision checker
places what the hand carries at every configuration it checks)."""

from __future__ import annotations

import pybullet as p

from kitchen_tamp.world.attachment import Attachment
from kitchen_tamp.world.bodies import BASE_LINK
from kitchen_tamp.world.transforms import Pose


class CarriedPlacement:
    """Moves a carried body with its parent link, in raw PyBullet transforms when it can."""

    def __init__(self, attachment: Attachment) -> None:
        parent, child = attachment.parent, attachment.child
        self.attachment = attachment
        self.client, self.parent_uid, self.child_uid = parent.client, parent.uid, child.uid
        self.link = parent.link_index(attachment.parent_link)
        child_com = Pose.from_parts(*p.getBasePositionAndOrientation(child.uid, physicsClientId=self.client))
        offset = attachment.parent_link_from_child @ child.base_pose().inverse() @ child_com
        self.offset = (offset.position, offset.quaternion)

    def apply(self) -> None:
        """Put the child where its parent link now says."""
        if self.link == BASE_LINK:
            self.attachment.apply()
            return
        link = p.getLinkState(
            self.parent_uid, self.link, computeForwardKinematics=True, physicsClientId=self.client
        )
        world = p.multiplyTransforms(link[4], link[5], *self.offset)
        p.resetBasePositionAndOrientation(self.child_uid, world[0], world[1], physicsClientId=self.client)
