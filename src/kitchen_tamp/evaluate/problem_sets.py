"""Named sets of shipped problems for a sweep (``--problem-set``), each problem with the name
the results table gives it.

``benchmarks``: every problem of the benchmark families (``shipped_kitchens/benchmarks/<family>/``,
docs/tamp.md), named after its family (``nonmonotonic``), and its file's suffix when a family
has several (``towers-sussman`` for ``towers/problem_sussman.pddl``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Final

from kitchen_tamp.shipped_kitchens import kitchen_folder

BENCHMARKS: Final = "benchmarks"
PROBLEM_SETS: Final = (BENCHMARKS,)
PROBLEM_PREFIX: Final = "problem"


def problem_set(name: str) -> dict[Path, str]:
    """The problem files of the set ``name`` and their names, in the set's order."""
    if name != BENCHMARKS:
        raise ValueError(f"unknown problem set {name!r}; choose from {', '.join(PROBLEM_SETS)}")
    named: dict[Path, str] = {}
    for problem in sorted(kitchen_folder(BENCHMARKS).glob(f"*/{PROBLEM_PREFIX}*.pddl")):
        family, suffix = problem.parent.name, problem.stem.removeprefix(PROBLEM_PREFIX).lstrip("_")
        named[problem.resolve()] = f"{family}-{suffix}" if suffix else family
    return named
