"""The kitchens that ship with kitchen_tamp, as package data: one folder per kitchen with its
scene file (``scene.toml``), and its PDDL problems (the ``default`` kitchen also holds the
domain every kitchen shares).

Only ``os.path`` is used here (and the file-name rule of ``planning.pddl_paths``), so the
command lines find the shipped files without loading the simulator, and the activity
planner's start-up (``find_problem_file``, ``domain_file_for``: plain strings) loads
neither ``importlib.resources`` nor ``pathlib``.
"""

from __future__ import annotations

import os

from kitchen_tamp.planning.reading.paths import is_bare_name

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from pathlib import Path
    from typing import Final

DEFAULT_KITCHEN: Final = "default"
SCENE_FILE: Final = "scene.toml"
DOMAIN_FILE: Final = "domain.pddl"
DEFAULT_PROBLEM: Final = "problem.pddl"


def _package_folder() -> str:
    folder = os.path.dirname(os.path.abspath(__file__))
    if not os.path.isdir(folder):  # wheels install packages as plain files; a zip import would not
        raise RuntimeError(f"the shipped kitchens are not on the file system ({folder})")
    return folder


def _as_path(path: str) -> Path:
    from pathlib import Path  # on use: the planner's start-up works on plain strings

    return Path(path)


def _kitchen_folder(name: str = DEFAULT_KITCHEN) -> str:
    return os.path.join(_package_folder(), name)


def kitchen_folder(name: str = DEFAULT_KITCHEN) -> Path:
    """The folder of a shipped kitchen."""
    return _as_path(_kitchen_folder(name))


def shipped_kitchens() -> list[str]:
    """Names of the kitchens that ship with the package."""
    folder = _package_folder()
    return sorted(name for name in os.listdir(folder)
                  if os.path.isfile(os.path.join(folder, name, SCENE_FILE)))


def default_scene_path() -> Path:
    """The default kitchen's scene file."""
    return _as_path(os.path.join(_kitchen_folder(), SCENE_FILE))


def _default_domain_file() -> str:
    return os.path.join(_kitchen_folder(), DOMAIN_FILE)


def default_domain_path() -> Path:
    """The kitchen domain, shared by every shipped kitchen."""
    return _as_path(_default_domain_file())


def _problem_folders() -> list[str]:
    names = [DEFAULT_KITCHEN, *(n for n in shipped_kitchens() if n != DEFAULT_KITCHEN)]
    return [_kitchen_folder(n) for n in names]


def problem_folders() -> list[Path]:
    """Where bare problem names are looked up after the working directory: the default
    kitchen first, then the others in name order."""
    return [_as_path(folder) for folder in _problem_folders()]


def find_problem_file(problem: str, scene: str | None = None) -> str:
    """``find_problem`` as a plain string (the file as given if it exists or names a folder)."""
    if os.path.exists(problem or ".") or not is_bare_name(problem):
        return problem
    folders = ([os.path.dirname(scene)] if scene is not None else []) + _problem_folders()
    for folder in folders:
        if os.path.isfile(os.path.join(folder, problem)):
            return os.path.join(folder, problem)
    return problem


def find_problem(problem: str | os.PathLike[str], scene: str | os.PathLike[str] | None = None) -> Path:
    """A problem file as given if it exists or names a folder; else a bare name looked up in
    the working directory, beside ``scene``, then in the shipped kitchens (the path as given
    if none has it, so the caller reports it missing)."""
    return _as_path(find_problem_file(os.fspath(problem), None if scene is None else os.fspath(scene)))


def scene_for(problem: Path) -> Path:
    """The scene of a problem: ``scene.toml`` beside it, else the default kitchen's."""
    beside = problem.parent / SCENE_FILE
    return beside if beside.is_file() else default_scene_path()


def domain_file_for(problem: str) -> str:
    """``domain_for`` as a plain string."""
    beside = os.path.join(os.path.dirname(problem), DOMAIN_FILE)
    return beside if os.path.isfile(beside) else _default_domain_file()


def domain_for(problem: str | os.PathLike[str]) -> Path:
    """The domain of a problem: ``domain.pddl`` beside it, else the shipped kitchen domain."""
    return _as_path(domain_file_for(os.fspath(problem)))
