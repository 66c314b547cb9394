"""The verdict of execution under physics and the figures behind it, and the bounds it is held
to: how far the simulated scene may be from what the kinematic judge read in the plan, how
far the arm may lag its command, and how hard the robot may touch what it should not."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from kitchen_tamp.execute.atom_comparison import all_hold
from kitchen_tamp.execute.physics.time_law import DEFAULT_TIME_LAW, TimeLaw
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.world import Pose
from kitchen_tamp.world.physics import DEFAULT_PHYSICS, PhysicsSettings


@dataclass(frozen=True)
class PhysicsTolerances:
    """How far the simulated scene may be from the plan, and how long it may take to settle."""

    position_m: float = 0.02
    tilt_deg: float = 10.0
    slip_m: float = 0.02
    slip_deg: float = 10.0
    tracking_rad: float = 0.05
    """Largest lag of any arm joint behind its commanded position (a trajectory the arm cannot
    follow, or one pressing into something, lags far more)."""
    contact_force_n: float = 0.0
    """An unplanned contact of the robot pressing harder than this (N) is a problem."""
    still_speed: float = 0.002
    """A body moving slower than this (m/s, and rad/s x 0.1 m) counts as still."""
    settle_s: float = 1.0
    """Longest wait for the scene to come to rest after an action or a gripper change."""


DEFAULT_TOLERANCES = PhysicsTolerances()


@dataclass(frozen=True)
class PhysicsConfiguration:
    """How execution under physics is run and judged."""

    settings: PhysicsSettings = DEFAULT_PHYSICS
    time_law: TimeLaw = DEFAULT_TIME_LAW
    tolerances: PhysicsTolerances = DEFAULT_TOLERANCES
    frame_interval_s: float = 1.0 / 30.0
    """Simulated time between two calls of ``on_frame``."""


DEFAULT_CONFIGURATION = PhysicsConfiguration()


@dataclass
class ActionFigures:
    """What one action did under physics."""

    action: str
    max_joint_error_rad: float = 0.0
    held_box: str | None = None
    max_slip_m: float = 0.0
    max_slip_deg: float = 0.0
    max_unplanned_force_n: float = 0.0
    as_planned: bool = True
    box_errors: dict[str, dict[str, float]] = field(default_factory=dict)
    drawer_errors_m: dict[str, float] = field(default_factory=dict)
    end_s: float = 0.0
    """Simulated time when the scene was compared with the plan after the action."""

    def data(self) -> dict[str, object]:
        return {
            "action": self.action,
            "max_joint_error_rad": round(self.max_joint_error_rad, 5),
            "held_box": self.held_box,
            "max_slip_m": round(self.max_slip_m, 5),
            "max_slip_deg": round(self.max_slip_deg, 3),
            "max_unplanned_contact_force_n": round(self.max_unplanned_force_n, 3),
            "as_planned": self.as_planned,
            "box_errors": self.box_errors,
            "drawer_errors_m": {k: round(v, 5) for k, v in self.drawer_errors_m.items()},
            "end_s": round(self.end_s, 4),
        }


@dataclass(frozen=True, eq=False)
class Replan:
    """The rest of a plan refined again from the simulated scene after step ``after`` (1-based)
    had drifted beyond tolerance (``reason``); None when the re-planner found nothing."""

    after: int
    reason: str
    trajectory: KitchenTrajectory | None

    def data(self) -> dict[str, object]:
        return {
            "after_step": self.after,
            "reason": self.reason,
            "plan": None if self.trajectory is None else self.trajectory.plan,
        }


@dataclass
class PhysicsExecution:
    """The verdict of execution under physics and the figures behind it."""

    configuration: PhysicsConfiguration
    actions: list[ActionFigures] = field(default_factory=list)
    goal_atoms: dict[str, bool] = field(default_factory=dict)
    final_atoms: list[str] = field(default_factory=list)
    final_box_errors: dict[str, dict[str, float]] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)
    worst_unplanned_contact: dict[str, object] | None = None
    replan: Replan | None = None
    """Set when a re-planner was given and the scene drifted: execution stopped there."""
    replans: list[dict[str, object]] = field(default_factory=list)
    """The re-plans of the planning run that wrote the trajectory (none in a replay)."""
    simulated_s: float = 0.0

    @property
    def goal_reached(self) -> bool:
        return all_hold(self.goal_atoms)

    @property
    def verified(self) -> bool:
        return all(a.as_planned for a in self.actions) and self.goal_reached and not self.problems

    def report_data(self) -> dict[str, object]:
        """The ``physics`` section of a report."""
        tolerances, settings = self.configuration.tolerances, self.configuration.settings
        return {
            "verified": self.verified,
            "goal_atoms": dict(self.goal_atoms),
            "final_atoms": list(self.final_atoms),
            "final_box_errors": self.final_box_errors,
            "max_joint_error_rad": round(max((a.max_joint_error_rad for a in self.actions), default=0.0), 5),
            "worst_unplanned_contact": self.worst_unplanned_contact,
            "actions": [a.data() for a in self.actions],
            "problems": list(self.problems),
            "replans": list(self.replans),
            "simulated_s": round(self.simulated_s, 3),
            "tolerances": {
                "position_m": tolerances.position_m,
                "tilt_deg": tolerances.tilt_deg,
                "slip_m": tolerances.slip_m,
                "slip_deg": tolerances.slip_deg,
                "tracking_rad": tolerances.tracking_rad,
                "unplanned_contact_force_n": tolerances.contact_force_n,
            },
            "settings": {
                "time_step_s": settings.time_step,
                "grip_force_n": settings.grip_force,
                "grip_squeeze_m": settings.grip_squeeze,
                "passive_joint_friction": settings.passive_joint_friction,
                "box_friction": settings.box_material.lateral,
                "polyhedral_contacts": settings.polyhedral_contacts,
                "speed_fraction": self.configuration.time_law.speed_fraction,
            },
        }


def pose_errors(planned: Pose, actual: Pose) -> dict[str, float]:
    """Position error (m), tilt (deg: angle between the planned and actual box up-axes as
    seen in the world) and whole rotation error (deg) of a box."""
    position, rotation = actual.distance_to(planned)
    up_planned = planned.rotation.T @ np.array([0.0, 0.0, 1.0])
    up_actual = actual.rotation.T @ np.array([0.0, 0.0, 1.0])
    tilt = float(np.degrees(np.arccos(np.clip(np.dot(up_planned, up_actual), -1.0, 1.0))))
    return {
        "position_error_m": round(position, 5),
        "tilt_deg": round(tilt, 3),
        "rotation_deg": round(float(np.degrees(rotation)), 3),
    }
