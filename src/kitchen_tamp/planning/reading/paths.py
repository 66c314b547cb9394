"""Finding and reading PDDL files: cheap to import (no Lark, no ``pddl`` package, no ``pathlib``).

A run served from the task cache (``task_cache``) needs these and nothing of
the parser, so they live apart from ``pddl_files``.
"""

from __future__ import annotations

import os

from kitchen_tamp.planning.errors import PlanningInputError

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from pathlib import Path

PDDL_FOLDER = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.realpath(__file__)))))), "pddl")
"""The repository's ``pddl/`` folder, where bare problem names are also looked up."""


def is_bare_name(path: str) -> bool:
    """A name without a folder, as ``pathlib`` has it (``Path(path).parent == Path(".")``)."""
    if os.path.isabs(path):
        return False
    if os.altsep:
        path = path.replace(os.altsep, os.sep)
    return len([part for part in path.split(os.sep) if part not in ("", ".")]) <= 1


def resolve_problem_file(problem: str | os.PathLike[str]) -> str:
    """The problem file: as given, else a bare name looked up in ``pddl/``; a plain string, for
    start-up code that does without ``pathlib``.

    This lets ``activity_planning.py problem_hard.pddl`` work from the
    repository root as well as from inside ``pddl/``.
    """
    given = os.fspath(problem)
    if os.path.exists(given or ".") or not is_bare_name(given):
        return given
    candidate = os.path.join(PDDL_FOLDER, given)
    return candidate if os.path.exists(candidate) else given




def read_pddl(path: str | Path, what: str) -> str:
    """The text of a PDDL file; a missing or unreadable file is an input error naming ``what``."""
    if not os.path.exists(path):
        raise PlanningInputError(f"{what} file not found", path)
    if os.path.isdir(path):
        raise PlanningInputError(f"{what} path is a directory, expected a PDDL file", path)
    try:
        with open(path, encoding="utf-8") as stream:
            return stream.read()
    except (OSError, UnicodeDecodeError) as error:
        raise PlanningInputError(f"cannot read {what} file: {error}", path) from error
