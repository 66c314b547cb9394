"""``report.json``: what a run planned, what each step took, and what verification found.

Everything outside ``timing`` is deterministic for a given problem, mode and
seed, so two runs can be compared by their reports with ``timing`` removed.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from kitchen_tamp.atomic_files import write_atomically

REPORT_FORMAT = "kitchen_tamp.report/1"
REPORT_FILE = "report.json"
PHASES = ("startup_s", "symbolic_s", "refinement_s", "verification_s", "physics_s", "rendering_s")
"""The ``timing`` entries that follow one another in the main process, from its start (imports
included) to the report; ``total_s`` is their sum plus ``other_s`` (writing trajectory.json, the
verdict line, re-judging after a re-plan). Others are parts of these (``skills_s``, ``motion_s``,
``judge_replay_s``, ``checkers_s`` of ``refinement_s``; ``html_s``, ``joints_s``,
``pictures_wait_s`` of ``rendering_s``) or ran beside them in a second process (``gif_s``;
``joints_s`` without a GIF; ``physics_run_s``, physics executing beside the kinematic judge, of
which ``physics_s`` is only what the main process waited for it after the judge)."""


@dataclass
class RunReport:
    """A report under construction; ``data()`` gives the JSON document."""

    problem: Path
    domain: Path
    mode: str
    motion_planner: str
    seed: int
    symbolic_planner: str = "bfs"
    scene: Path | None = None
    """The kitchen scene file the run planned in (or is judged in)."""
    inputs: dict[str, object] | None = None
    """The ``inputs`` section: each input file's path, SHA-256 and whether it is the run's."""
    plan: list[str] | None = None
    steps: list[dict[str, object]] = field(default_factory=list)
    failure: dict[str, object] | None = None
    verification: dict[str, object] | None = None
    bilevel: dict[str, object] | None = None
    physics: dict[str, object] | None = None
    """The ``physics`` section (execution under physics), None when it was skipped."""
    outputs: dict[str, str | None] = field(default_factory=dict)
    timing: dict[str, object] = field(default_factory=dict)
    started: float | None = None
    """``time.perf_counter()`` when the run began; the report's ``timing.total_s`` counts from it."""

    @property
    def solved(self) -> bool:
        """Refined and verified (under physics too, unless physics was skipped)."""
        physics_ok = self.physics is None or bool(self.physics["verified"])
        return (
            self.failure is None
            and self.verification is not None
            and bool(self.verification["verified"])
            and physics_ok
        )

    def verdicts(self) -> str:
        """Both judges' verdicts in words, e.g. ``kinematic judge: verified, physics: FAILED``."""
        if self.verification is None:
            kinematic = "not run"
        else:
            kinematic = "verified" if self.verification["verified"] else "FAILED"
        if self.physics is None:
            physics = "skipped" if self.verification is not None else "not run"
        else:
            physics = "verified" if self.physics["verified"] else "FAILED"
            replans = self.physics.get("replans") or []
            if isinstance(replans, list) and replans:
                physics += f" after {len(replans)} re-plan{'s' if len(replans) > 1 else ''}"
            errors = self.physics.get("final_box_errors") or {}
            if isinstance(errors, dict) and errors:
                position = max(float(e["position_error_m"]) for e in errors.values())
                tilt = max(float(e["tilt_deg"]) for e in errors.values())
                physics += f" (boxes within {position * 1000:.1f} mm and {tilt:.1f} deg of the plan)"
        return f"kinematic judge: {kinematic}, physics: {physics}"

    def fail(self, stage: str, reason: str, step: int | None = None, action: str | None = None) -> None:
        """Record why the run did not solve the problem (the first failure wins)."""
        if self.failure is None:
            self.failure = {"stage": stage, "step": step, "action": action, "reason": reason}

    def unaccounted_seconds(self) -> float:
        """``total_s`` less the phases (`PHASES`) it holds: what no phase accounts for."""
        total = self.timing.get("total_s")
        phases = [self.timing.get(phase) for phase in PHASES]
        counted = sum(value for value in phases if isinstance(value, float))
        return float(total) - counted if isinstance(total, float) else 0.0

    def data(self) -> dict[str, Any]:
        return {
            "format": REPORT_FORMAT,
            "problem": self.problem.name,
            "problem_path": str(self.problem),
            "domain_path": str(self.domain),
            "scene_path": None if self.scene is None else str(self.scene),
            "inputs": self.inputs,
            "mode": self.mode,
            "motion_planner": self.motion_planner,
            "seed": self.seed,
            "symbolic_planner": self.symbolic_planner,
            "plan": self.plan,
            "solved": self.solved,
            "failure": self.failure,
            "steps": self.steps,
            "bilevel": self.bilevel,
            "verification": self.verification,
            "physics": self.physics,
            "outputs": self.outputs,
            "timing": {k: round(v, 4) if isinstance(v, float) else v for k, v in self.timing.items()},
        }

    def write(self, path: Path) -> Path:
        """Write the report to ``path`` (normally ``RUN_DIR/report.json``) atomically."""
        return write_atomically(path, json.dumps(self.data(), indent=2) + "\n")
