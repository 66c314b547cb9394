"""The loop every skill runs: draw a candidate (a grasp, a placement), build its segments, hand
out targets -- or, when the budget is spent, fail saying why (``SkillFailure``: its kind and the
objects to blame, from what the rejected candidates ran into).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Protocol, TypeVar

import numpy as np

from kitchen_tamp.kitchen.errors import FailureKind, SkillFailure
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.targets import SkillTargets
from kitchen_tamp.world import FloatArray, PyBulletCollisionChecker

Candidate = TypeVar("Candidate")


@dataclass
class Rejections:
    """What the rejected candidates of one skill ran into. ``own`` are the action's own boxes
    (never obstructions); ``region`` is where the skill acts."""

    kitchen: KitchenScene
    own: tuple[str, ...] = ()
    region: str | None = None
    blockers: Counter[str] = field(default_factory=Counter)
    occupants: Counter[str] = field(default_factory=Counter)
    crowded: int = 0
    """Candidate placements that overlapped objects already there."""
    free: int = 0
    """Candidate placements that did not."""

    def collided(self, checker: PyBulletCollisionChecker, q: FloatArray) -> None:
        """Note the other boxes ``checker`` finds in collision at ``q`` (a rejected configuration)."""
        names = {side.split("/")[0] for pair in checker.colliding_pairs(q) for side in pair}
        self.blockers.update(sorted(n for n in names if n in self.kitchen.boxes and n not in self.own))

    def placement(self, overlapping: Iterable[str]) -> bool:
        """Note a candidate placement and the boxes it overlaps; whether it is free."""
        names = sorted(overlapping)
        if names:
            self.crowded += 1
            self.occupants.update(names)
            return False
        self.free += 1
        return True

    def failure(self, action: str, detail: str) -> SkillFailure:
        """The failure these rejections amount to."""
        if self.crowded and not self.free:
            kind, objects = FailureKind.FULL, _most_first(self.occupants)
            return SkillFailure(action, detail, kind, objects, self.region)
        if self.blockers:
            kind, objects = FailureKind.OBSTRUCTED, _most_first(self.blockers)
            return SkillFailure(action, detail, kind, objects, self.region)
        return SkillFailure(action, detail, FailureKind.UNREACHABLE, (), self.region)


def _most_first(counts: Counter[str]) -> tuple[str, ...]:
    return tuple(name for name, _ in sorted(counts.items(), key=lambda item: (-item[1], item[0])))


class SkillProblem(Protocol[Candidate]):
    """One skill's sampling: what its candidates share and how each becomes segments."""

    @property
    def action_text(self) -> str: ...

    def draw(self, rng: np.random.Generator, rejections: Rejections) -> Candidate | None:
        """A random candidate, or None when this draw gives nothing to try (the attempt is spent)."""
        ...

    def segments(
        self, candidate: Candidate, rng: np.random.Generator, rejections: Rejections
    ) -> tuple[Segment, ...] | None:
        """The candidate's scripted segments, or None if any of them is infeasible."""
        ...

    def targets(self, segments: tuple[Segment, ...], samples_tried: int) -> SkillTargets:
        """The targets of a feasible candidate."""
        ...

    def exhausted(self, attempts: int) -> str:
        """Why the skill failed when no candidate of ``attempts`` was feasible."""
        ...


def sample_skill(
    problem: SkillProblem[Candidate],
    rng: np.random.Generator,
    parameters: SkillParameters,
    rejections: Rejections,
) -> SkillTargets:
    """The targets of the first feasible candidate among ``parameters.attempts`` draws; raises
    ``SkillFailure`` (kind and objects from ``rejections``) when none is."""
    for attempt in range(1, parameters.attempts + 1):
        candidate = problem.draw(rng, rejections)
        if candidate is None:
            continue
        segments = problem.segments(candidate, rng, rejections)
        if segments is not None:
            return problem.targets(segments, attempt)
    raise rejections.failure(problem.action_text, problem.exhausted(parameters.attempts))
