"""The kitchens that ship with kitchen_tamp, as package data: one folder per kitchen with its
scene file (``scene.toml``), and its PDDL problems (the ``default`` kitchen also holds the
domain every kitchen shares).

Only the standard library is used here, so the command lines can find the shipped files
without loading the simulator.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path
from typing import Final

DEFAULT_KITCHEN: Final = "default"
SCENE_FILE: Final = "scene.toml"
DOMAIN_FILE: Final = "domain.pddl"
DEFAULT_PROBLEM: Final = "problem.pddl"


def _package_folder() -> Path:
    folder = files(__name__)
    if not isinstance(folder, Path):  # wheels install packages as plain files; a zip import would not
        raise RuntimeError(f"the shipped kitchens are not on the file system ({folder})")
    return folder


def kitchen_folder(name: str = DEFAULT_KITCHEN) -> Path:
    """The folder of a shipped kitchen."""
    return _package_folder() / name


def shipped_kitchens() -> list[str]:
    """Names of the kitchens that ship with the package."""
    return sorted(p.name for p in _package_folder().iterdir() if (p / SCENE_FILE).is_file())


def default_scene_path() -> Path:
    """The default kitchen's scene file."""
    return kitchen_folder() / SCENE_FILE


def default_domain_path() -> Path:
    """The kitchen domain, shared by every shipped kitchen."""
    return kitchen_folder() / DOMAIN_FILE


def problem_folders() -> list[Path]:
    """Where bare problem names are looked up after the working directory: the default
    kitchen first, then the others in name order."""
    names = [DEFAULT_KITCHEN, *(n for n in shipped_kitchens() if n != DEFAULT_KITCHEN)]
    return [kitchen_folder(n) for n in names]


def find_problem(problem: str | Path, scene: Path | None = None) -> Path:
    """A problem file as given if it exists or names a folder; else a bare name looked up in
    the working directory, beside ``scene``, then in the shipped kitchens (the path as given
    if none has it, so the caller reports it missing)."""
    path = Path(problem)
    if path.exists() or path.parent != Path("."):
        return path
    folders = ([scene.parent] if scene is not None else []) + problem_folders()
    for folder in folders:
        if (folder / path).is_file():
            return folder / path
    return path


def scene_for(problem: Path) -> Path:
    """The scene of a problem: ``scene.toml`` beside it, else the default kitchen's."""
    beside = problem.parent / SCENE_FILE
    return beside if beside.is_file() else default_scene_path()


def domain_for(problem: Path) -> Path:
    """The domain of a problem: ``domain.pddl`` beside it, else the shipped kitchen domain."""
    beside = problem.parent / DOMAIN_FILE
    return beside if beside.is_file() else default_domain_path()
