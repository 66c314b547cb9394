"""The one rule that finds a problem's files: as given, else the working directory, beside the
scene, the shipped kitchens; the domain and scene beside the problem, else the shipped ones."""

from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.shipped_kitchens import (
    default_domain_path,
    default_scene_path,
    domain_for,
    find_problem,
    kitchen_folder,
    problem_folders,
    scene_for,
    shipped_kitchens,
)


@pytest.fixture
def elsewhere(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working directory with nothing in it."""
    folder = tmp_path / "work"
    folder.mkdir()
    monkeypatch.chdir(folder)
    return folder


def test_a_bare_name_is_found_in_the_shipped_kitchens_from_any_folder(elsewhere: Path) -> None:
    found = find_problem("problem_hard.pddl")
    assert found == kitchen_folder() / "problem_hard.pddl" and found.is_file()
    galley = next(name for name in shipped_kitchens() if name != "default")
    only_there = next(p.name for p in kitchen_folder(galley).glob("*.pddl")
                      if not (kitchen_folder() / p.name).exists())
    assert find_problem(only_there) == kitchen_folder(galley) / only_there
    assert problem_folders()[0] == kitchen_folder()


def test_the_working_directory_comes_first_then_the_scene_s_folder(elsewhere: Path, tmp_path: Path) -> None:
    scene_folder = tmp_path / "mykitchen"
    scene_folder.mkdir()
    (scene_folder / "problem_hard.pddl").write_text("beside the scene")
    scene = scene_folder / "scene.toml"
    assert find_problem("problem_hard.pddl", scene) == scene_folder / "problem_hard.pddl"
    (elsewhere / "problem_hard.pddl").write_text("in the working directory")
    assert find_problem("problem_hard.pddl", scene) == Path("problem_hard.pddl")


def test_a_name_with_a_folder_or_found_nowhere_is_taken_as_given(elsewhere: Path) -> None:
    assert find_problem("pddl/problem_hard.pddl") == Path("pddl/problem_hard.pddl")
    assert find_problem("no_such_problem.pddl") == Path("no_such_problem.pddl")


def test_domain_and_scene_beside_the_problem_else_the_shipped_ones(tmp_path: Path) -> None:
    problem = tmp_path / "problem.pddl"
    assert domain_for(problem) == default_domain_path() and default_domain_path().is_file()
    assert scene_for(problem) == default_scene_path() and default_scene_path().is_file()
    (tmp_path / "domain.pddl").write_text("")
    (tmp_path / "scene.toml").write_text("")
    assert domain_for(problem) == tmp_path / "domain.pddl"
    assert scene_for(problem) == tmp_path / "scene.toml"
