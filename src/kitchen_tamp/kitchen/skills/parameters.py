"""Hyper-parameters of the kitchen skills (distances and budgets, never joint angles)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SkillParameters:
    """How the skills sample and move; all lengths in metres, angles in radians."""

    pregrasp_distance: float = 0.09
    """The hand stops this far back along the approach before going straight in."""
    lift_height: float = 0.10
    """A picked box is lifted at least this high; more to clear a drawer's walls."""
    wall_clearance: float = 0.03
    """Extra height above a tray's walls for a box lifted out of it or lowered in."""
    waypoint_step: float = 0.01
    """Spacing of the Cartesian waypoints of approach, lift, pull and retreat."""
    max_joint_step: float = 0.2
    """Largest joint change between two Cartesian waypoints (else IK changed branch)."""
    finger_clearance: float = 0.01
    """A box fits the gripper if it is this much narrower than the fingers' full opening."""
    finger_pad_half_width: float = 0.012
    """Half the fingers' extent across the closing direction: grasps keep it on the object."""
    grasp_depth: tuple[float, float] = (0.012, 0.03)
    """How far past a box face the tool point (between the finger pads) goes."""
    keep_down_probability: float = 0.5
    """Chance that a placement keeps down the box face that was down when it was picked."""
    hand_above_probability: float = 0.4
    """Chance that a placement puts down the face the hand approached, so the hand is above
    the box (any face otherwise)."""
    free_space_clearance: float = 0.005
    """Where a skill hands over to free-space motion (before its approach, after its
    retreat) the arm and what it carries keep at least this clearance, so a motion
    planner keeping a small margin can start and end there."""
    neighbour_clearance: float = 0.003
    """The straight moves of pick and place (approach, lift, descent, retreat) keep the hand
    and the held box at least this far from every box but the one handled and what it
    stands on or goes onto. Under physics the hand lags its plan and PyBullet makes a
    contact within 1 mm (``PhysicsSettings.contact_breaking_threshold``): a hand that
    passed a neighbour 0.05-0.3 mm away pushed it (0.04-3.7 N) in the benchmark sweeps."""
    ik_solutions: int = 4
    """IK solutions of one target pose tried for being collision-free before the next sample."""
    attempts: int = 40
    """Samples a skill tries before it gives up."""
    placement_draws: int = 20
    """Poses one placement sample may draw until one is clear of the boxes already there
    (drawing costs no motion; the first is clear on an empty region)."""
    packed_probability: float = 0.75
    """Chance that a placement attempt on a region that already holds boxes first tries the next
    packed pose (flush against the region's edges and the boxes there) before drawing uniform
    poses; an attempt whose uniform draws are all crowded always does. Uniform poses alone
    scatter boxes at random yaws until the room left is in pieces none of which fits one more
    (the packed plate's fifth block)."""
    placement_gap: float = 0.006
    """A placed box keeps at least this far from the boxes beside it (footprint to footprint).
    Under physics a released box settles up to about 2 mm from where the plan put it, and
    PyBullet makes a contact within 1 mm (``PhysicsSettings.contact_breaking_threshold``): two
    neighbours that settle towards each other must still not touch, or the later pick of one
    drags the other into the fingers. 3 mm left no room for that; a wider gap packs fewer
    boxes into a region (the packed plate's five blocks)."""

    def __post_init__(self) -> None:
        if min(self.pregrasp_distance, self.lift_height, self.waypoint_step, self.max_joint_step) <= 0:
            raise ValueError(f"skill distances must be positive: {self}")
        if self.neighbour_clearance < 0:
            raise ValueError(f"the neighbour clearance must not be negative: {self.neighbour_clearance}")
        probabilities = (self.keep_down_probability, self.hand_above_probability)
        budgets = min(self.attempts, self.placement_draws)
        packing = 0.0 <= self.packed_probability <= 1.0
        if min(probabilities) < 0.0 or sum(probabilities) > 1.0 or budgets < 1 or not packing:
            raise ValueError(f"invalid skill parameters: {self}")
        if not 0.0 < self.grasp_depth[0] <= self.grasp_depth[1]:
            raise ValueError(f"grasp depth range must be increasing and positive: {self.grasp_depth}")


DEFAULT_PARAMETERS = SkillParameters()
