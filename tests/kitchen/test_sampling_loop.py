"""The one skill sampling loop: first feasible candidate wins, the budget is counted, and the
failure says why from what the rejected candidates ran into (no simulator needed)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pytest

from kitchen_tamp.kitchen import FailureKind, SkillFailure
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.parameters import SkillParameters
from kitchen_tamp.kitchen.skills.sampling_loop import Rejections, sample_skill
from kitchen_tamp.kitchen.skills.targets import SkillTargets


@dataclass
class CountingProblem:
    """Candidates are the draw numbers; ``feasible`` ones get segments; ``crowded`` draws overlap
    boxes; ``empty`` draws give nothing to try."""

    feasible: set[int] = field(default_factory=set)
    crowded: dict[int, tuple[str, ...]] = field(default_factory=dict)
    empty: set[int] = field(default_factory=set)
    draws: int = 0
    built: list[int] = field(default_factory=list)

    @property
    def action_text(self) -> str:
        return "(test a)"

    def draw(self, rng: np.random.Generator, rejections: Rejections) -> int | None:
        self.draws += 1
        if self.draws in self.empty:
            return None
        if not rejections.placement(self.crowded.get(self.draws, ())):
            return None
        return self.draws

    def segments(
        self, candidate: int, rng: np.random.Generator, rejections: Rejections
    ) -> tuple[Segment, ...] | None:
        self.built.append(candidate)
        if candidate not in self.feasible:
            rejections.blockers.update(["b"])
            return None
        q = np.zeros((2, 7))
        return (Segment("still", q, np.zeros(2)),)

    def targets(self, segments: tuple[Segment, ...], samples_tried: int) -> SkillTargets:
        raise Chosen(samples_tried)

    def exhausted(self, attempts: int) -> str:
        return f"nothing in {attempts} samples"


class Chosen(Exception):
    """Stands in for targets (which need a scene): carries the attempt that succeeded."""

    def __init__(self, attempt: int) -> None:
        super().__init__(attempt)
        self.attempt = attempt


def run(problem: CountingProblem, attempts: int = 5) -> SkillTargets:
    rejections = Rejections(kitchen=None, own=("a",), region="shelf")  # type: ignore[arg-type]
    return sample_skill(problem, np.random.default_rng(0), SkillParameters(attempts=attempts), rejections)


def test_the_first_feasible_candidate_is_taken_and_its_attempt_counted() -> None:
    problem = CountingProblem(feasible={3, 4}, empty={2})
    with pytest.raises(Chosen) as chosen:
        run(problem)
    assert chosen.value.attempt == 3
    assert problem.built == [1, 3]  # the empty draw spent attempt 2 without building anything


def test_candidates_that_ran_into_objects_fail_as_obstructed() -> None:
    with pytest.raises(SkillFailure) as failed:
        run(CountingProblem())
    failure = failed.value
    assert failure.kind is FailureKind.OBSTRUCTED and failure.objects == ("b",)
    assert failure.region == "shelf"
    assert str(failure) == "skill for (test a) failed: nothing in 5 samples"


def test_when_every_draw_overlapped_boxes_the_region_is_full() -> None:
    crowded = {i: ("c", "d") if i % 2 else ("d",) for i in range(1, 6)}
    with pytest.raises(SkillFailure) as failed:
        run(CountingProblem(crowded=crowded))
    assert failed.value.kind is FailureKind.FULL
    assert failed.value.objects == ("d", "c")  # most often in the way first


def test_nothing_to_blame_is_unreachable() -> None:
    with pytest.raises(SkillFailure) as failed:
        run(CountingProblem(empty=set(range(1, 6))))
    assert failed.value.kind is FailureKind.UNREACHABLE and failed.value.objects == ()
