"""The kitchens that ship with kitchen_tamp, and the one rule that finds a problem's files.

The kitchens are package data: one folder per kitchen with its scene file
(``scene.toml``) and its PDDL problems; the ``default`` kitchen also holds the
domain every kitchen shares. (The checkout's ``pddl/*.pddl`` are links to the
default kitchen's files.)

A command line names a problem, maybe a domain and a scene; ``find_problem``,
``domain_for`` and ``scene_for`` turn those into files, so that every program
finds them alike. A problem given with a folder, or one that exists where it
is named, is taken as given; a bare name is looked up in the working
directory, then beside the scene, then in the shipped kitchens (the default
kitchen first). The planning package takes the resulting paths and knows
nothing of this.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Final

DEFAULT_KITCHEN: Final = "default"
SCENE_FILE: Final = "scene.toml"
DOMAIN_FILE: Final = "domain.pddl"
DEFAULT_PROBLEM: Final = "problem.pddl"

PACKAGE_FOLDER: Final = Path(__file__).resolve().parent
"""Where the shipped kitchens are (wheels install package data as plain files)."""


def kitchen_folder(name: str = DEFAULT_KITCHEN) -> Path:
    """The folder of a shipped kitchen."""
    return PACKAGE_FOLDER / name


def shipped_kitchens() -> list[str]:
    """Names of the kitchens that ship with the package."""
    return sorted(folder.name for folder in PACKAGE_FOLDER.iterdir() if (folder / SCENE_FILE).is_file())


def default_scene_path() -> Path:
    """The default kitchen's scene file."""
    return kitchen_folder() / SCENE_FILE


def default_domain_path() -> Path:
    """The kitchen domain, shared by every shipped kitchen."""
    return kitchen_folder() / DOMAIN_FILE


def problem_folders() -> list[Path]:
    """Where bare problem names are looked up after the working directory (and the scene's
    folder): the default kitchen first, then the others in name order."""
    names = [DEFAULT_KITCHEN, *(name for name in shipped_kitchens() if name != DEFAULT_KITCHEN)]
    return [kitchen_folder(name) for name in names]


def find_problem(problem: str | os.PathLike[str], scene: str | os.PathLike[str] | None = None) -> Path:
    """A problem file as given if it exists or names a folder; else a bare name looked up in
    the working directory, beside ``scene``, then in the shipped kitchens (the path as given
    if none has it, so that loading reports it missing)."""
    given = Path(problem)
    if given.exists() or given.parent != Path("."):
        return given
    folders = ([Path(scene).parent] if scene is not None else []) + problem_folders()
    for folder in folders:
        if (folder / given).is_file():
            return folder / given
    return given


def scene_for(problem: Path) -> Path:
    """The scene of a problem: ``scene.toml`` beside it, else the default kitchen's."""
    beside = problem.parent / SCENE_FILE
    return beside if beside.is_file() else default_scene_path()


def domain_for(problem: Path) -> Path:
    """The domain of a problem: ``domain.pddl`` beside it, else the shipped kitchen domain."""
    beside = problem.parent / DOMAIN_FILE
    return beside if beside.is_file() else default_domain_path()
