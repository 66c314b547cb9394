"""Finding and reading PDDL files: cheap to import (no Lark, no ``pddl`` package).

A run served from the task cache (``task_cache``) needs these and nothing of
the parser, so they live apart from ``pddl_files``.
"""

from __future__ import annotations

from pathlib import Path

from kitchen_tamp.planning.errors import PlanningInputError

PDDL_DIR = Path(__file__).resolve().parents[3] / "pddl"
"""The repository's ``pddl/`` folder, where bare problem names are also looked up."""


def resolve_problem_path(problem: str | Path) -> Path:
    """The problem file: as given, else a bare name looked up in ``pddl/``.

    This lets ``activity_planning.py problem_hard.pddl`` work from the
    repository root as well as from inside ``pddl/``.
    """
    path = Path(problem)
    if path.exists() or path.parent != Path("."):
        return path
    candidate = PDDL_DIR / path
    return candidate if candidate.exists() else path


def read_pddl(path: Path, what: str) -> str:
    """The text of a PDDL file; a missing or unreadable file is an input error naming ``what``."""
    if not path.exists():
        raise PlanningInputError(f"{what} file not found", path)
    if path.is_dir():
        raise PlanningInputError(f"{what} path is a directory, expected a PDDL file", path)
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise PlanningInputError(f"cannot read {what} file: {error}", path) from error
