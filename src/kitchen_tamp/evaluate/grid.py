"""The sweep's grid: which (problem, mode, seed) tasks to run, each with a stable id."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

MODES = ("rrt", "optimizes")
"""The modes of ``final_project.py`` a sweep can run."""


class GridError(ValueError):
    """A grid that cannot be expanded (bad seed range, unknown mode, clashing problem names)."""


@dataclass(frozen=True)
class TaskSpec:
    """One run: ``final_project.py MODE --problem PROBLEM --seed SEED``."""

    problem: Path
    mode: str
    seed: int

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            raise GridError(f"unknown mode {self.mode!r}; choose from {', '.join(MODES)}")
        if self.seed < 0:
            raise GridError(f"seeds are non-negative, got {self.seed}")

    @property
    def problem_name(self) -> str:
        """The problem's file stem, as the results table names it."""
        return self.problem.stem

    @property
    def task_id(self) -> str:
        """Unique within a sweep; also the name of the task's run folder."""
        return f"{self.problem_name}-{self.mode}-seed{self.seed}"


def parse_seeds(text: str) -> tuple[int, ...]:
    """Seeds from ``"0-99"``, ``"7"`` or ``"0-4,10,12-13"``, in order, without repeats."""
    seeds: list[int] = []
    for part in text.split(","):
        part = part.strip()
        first, dash, last = part.partition("-")
        try:
            low = int(first)
            high = int(last) if dash else low
        except ValueError:
            raise GridError(f"bad seed range {part!r} in {text!r}: expected N or N-M") from None
        if low < 0 or high < low:
            raise GridError(f"bad seed range {part!r} in {text!r}: expected 0 <= N <= M")
        seeds.extend(s for s in range(low, high + 1) if s not in seeds)
    return tuple(seeds)


def check_distinct_names(problems: Sequence[Path]) -> None:
    """Raise ``GridError`` when two different problem files share a file stem (task ids would clash)."""
    stems: dict[str, Path] = {}
    for problem in problems:
        other = stems.setdefault(problem.stem, problem)
        if other != problem:
            raise GridError(f"two problems are both named {problem.stem!r}: {other} and {problem}")


def expand_grid(problems: Sequence[Path], modes: Sequence[str], seeds: Sequence[int]) -> list[TaskSpec]:
    """Every (problem, mode, seed), problem-major, without repeats."""
    check_distinct_names(problems)
    return [
        TaskSpec(problem, mode, seed)
        for problem in dict.fromkeys(problems)
        for mode in dict.fromkeys(modes)
        for seed in dict.fromkeys(seeds)
    ]
