"""Replaying a refined plan headless, verifying it independently of the planner, executing
it under physics, and
writing what a run leaves behind: report.json, trajectory.json, replay.gif, joints.png."""

from kitchen_tamp.execute.physics.execution import execute_under_physics, judge_under_physics, judged_pairs
from kitchen_tamp.execute.physics.verdict import PhysicsExecution
from kitchen_tamp.execute.run_report import REPORT_FILE, RunReport
from kitchen_tamp.execute.timeline import Timeline, build_timeline
from kitchen_tamp.execute.trajectory_file import (
    TRAJECTORY_FILE,
    SavedRun,
    TrajectoryFileError,
    read_trajectory,
    write_trajectory,
)
from kitchen_tamp.execute.verification import Verification, verify_trajectory

__all__ = [
    "REPORT_FILE",
    "TRAJECTORY_FILE",
    "PhysicsExecution",
    "RunReport",
    "SavedRun",
    "Timeline",
    "TrajectoryFileError",
    "Verification",
    "build_timeline",
    "execute_under_physics",
    "judge_under_physics",
    "judged_pairs",
    "read_trajectory",
    "verify_trajectory",
    "write_trajectory",
]
