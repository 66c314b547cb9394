"""The sweep's grid: which (problem, mode, seed) tasks to run, each with a stable id."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
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
    name: str | None = None
    """What the results table calls the problem (None: the file's stem)."""

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            raise GridError(f"unknown mode {self.mode!r}; choose from {', '.join(MODES)}")
        if self.seed < 0:
            raise GridError(f"seeds are non-negative, got {self.seed}")

    @property
    def problem_name(self) -> str:
        """The problem's name in the results table: its set's name for it, else its file stem."""
        return self.name or self.problem.stem

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


def check_distinct_names(problems: Sequence[Path], names: Mapping[Path, str] | None = None) -> None:
    """Raise ``GridError`` when two different problem files share a name (their ``names``
    entry, else their file stem): task ids would clash."""
    seen: dict[str, Path] = {}
    for problem in problems:
        name = (names or {}).get(problem, problem.stem)
        other = seen.setdefault(name, problem)
        if other != problem:
            raise GridError(f"two problems are both named {name!r}: {other} and {problem}")


def expand_grid(
    problems: Sequence[Path],
    modes: Sequence[str],
    seeds: Sequence[int],
    names: Mapping[Path, str] | None = None,
) -> list[TaskSpec]:
    """Every (problem, mode, seed), problem-major, without repeats; ``names`` name problems
    whose file stem would not do (a problem set's)."""
    check_distinct_names(problems, names)
    return [
        TaskSpec(problem, mode, seed, (names or {}).get(problem))
        for problem in dict.fromkeys(problems)
        for mode in dict.fromkeys(modes)
        for seed in dict.fromkeys(seeds)
    ]
