"""A body rigidly carried by a link of another body (a box in the hand, a box in a drawer)."""

from __future__ import annotations

from dataclasses import dataclass

from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.transforms import Pose


@dataclass(frozen=True)
class Attachment:
    """``child`` keeps the pose ``parent_link_from_child`` relative to ``parent``'s link."""

    parent: Body
    parent_link: str
    child: Body
    parent_link_from_child: Pose

    @staticmethod
    def from_current_poses(parent: Body, parent_link: str, child: Body) -> Attachment:
        """Attach ``child`` where it is now: its true pose relative to the link is kept."""
        world_from_link = parent.link_pose(parent_link)
        world_from_child = child.base_pose()
        return Attachment(parent, parent_link, child, world_from_link.inverse() @ world_from_child)

    def child_pose(self) -> Pose:
        """``world_from_child`` implied by the parent link's current pose."""
        return self.parent.link_pose(self.parent_link) @ self.parent_link_from_child

    def apply(self) -> None:
        """Move the child to follow its parent link."""
        self.child.reset_base_pose(self.child_pose())
