"""Random kitchen problems: valid PDDL over the kitchen map's objects, laid out in the kitchen,
planned symbolically, and the same files again from the same seed."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from types import MappingProxyType

import pytest

from kitchen_tamp.evaluate.random_problems import (
    RandomProblemError,
    generate_problems,
    kitchen_objects,
    write_manifest,
)
from kitchen_tamp.kitchen import build_kitchen_for_task, default_kitchen_map, load_kitchen_map
from kitchen_tamp.planning import load_task, plan, validate_plan
from kitchen_tamp.shipped_kitchens import default_scene_path, kitchen_folder

REPO = Path(__file__).resolve().parents[2]
DOMAIN = REPO / "pddl" / "domain.pddl"
REGIONS_DOMAIN = kitchen_folder("benchmarks") / "domain.pddl"


def _texts(folder: Path) -> dict[str, str]:
    return {p.name: p.read_text() for p in sorted(folder.glob("random-*.pddl"))}


@pytest.mark.slow
def test_problems_are_valid_lay_out_and_their_solvability_is_the_planners(tmp_path: Path) -> None:
    problems = generate_problems(6, 11, tmp_path, DOMAIN)
    assert [p.name for p in problems] == [f"random-{i:03d}" for i in range(6)]
    boxes_seen: set[str] = set()
    for problem in problems:
        task = load_task(problem.path, tmp_path / "domain.pddl")  # parses and grounds: valid PDDL
        assert set(task.objects) <= set(default_kitchen_map().object_names())
        assert not task.is_goal(task.initial_state)
        boxes_seen |= {name for name, kind in task.objects.items() if kind == "box"}
        with build_kitchen_for_task(task):  # raises unless the kitchen lays out :init
            pass
        result = plan(task, "bfs")
        assert problem.solvable == result.solved
        if result.plan is not None:
            assert problem.plan_length == len(result.plan)
            assert validate_plan(task, result.plan).valid
    assert len(boxes_seen) >= 2


@pytest.mark.slow
def test_same_seed_same_files_other_seed_other_files(tmp_path: Path) -> None:
    generate_problems(5, 4, tmp_path / "a", DOMAIN)
    generate_problems(5, 4, tmp_path / "b", DOMAIN)
    generate_problems(5, 5, tmp_path / "c", DOMAIN)
    assert _texts(tmp_path / "a") == _texts(tmp_path / "b")
    assert _texts(tmp_path / "a") != _texts(tmp_path / "c")
    assert (tmp_path / "a" / "domain.pddl").read_text() == DOMAIN.read_text()


def test_problems_of_another_seed_are_not_written_over(tmp_path: Path) -> None:
    generate_problems(2, 4, tmp_path, DOMAIN)
    before = _texts(tmp_path)
    generate_problems(2, 4, tmp_path, DOMAIN)  # the same seed again (--resume): same files, no error
    with pytest.raises(RandomProblemError, match=r"random-000\.pddl exists with other content"):
        generate_problems(2, 5, tmp_path, DOMAIN)
    assert _texts(tmp_path) == before


def test_objects_come_from_the_kitchen_map(tmp_path: Path) -> None:
    kitchen_map = default_kitchen_map()
    only_spam = replace(kitchen_map, boxes=MappingProxyType({"spam": kitchen_map.boxes["spam"]}))
    assert kitchen_objects(DOMAIN, only_spam).boxes == ("spam",)
    for problem in generate_problems(3, 0, tmp_path, DOMAIN, only_spam):
        objects = load_task(problem.path, tmp_path / "domain.pddl").objects
        assert {name for name, kind in objects.items() if kind == "box"} == {"spam"}


def test_a_domain_without_a_binding_is_refused(tmp_path: Path) -> None:
    domain = tmp_path / "domain.pddl"
    domain.write_text(DOMAIN.read_text().replace("cabClear", "drawerClear"))
    with pytest.raises(RandomProblemError, match=r"no skill binding for domain 'kitchen'"):
        generate_problems(1, 0, tmp_path / "out", domain)


@pytest.mark.slow
def test_problems_over_the_regions_domain_are_written_in_its_words_and_lay_out(tmp_path: Path) -> None:
    problems = generate_problems(3, 0, tmp_path, REGIONS_DOMAIN)
    assert (tmp_path / "domain.binding.toml").is_file()  # copied beside the domain
    kitchen_map = load_kitchen_map(default_scene_path(), tmp_path / "domain.pddl")
    for problem in problems:
        task = load_task(problem.path, tmp_path / "domain.pddl")
        words = {"on", "in", "clear", "handempty", "opened"}
        assert {predicate for predicate, *_ in task.init_atoms} <= words
        assert ("handempty",) in task.init_atoms
        with build_kitchen_for_task(task, kitchen_map=kitchen_map):
            pass
        assert problem.solvable == plan(task, "bfs").solved


def test_manifest_lists_every_problem(tmp_path: Path) -> None:
    problems = generate_problems(2, 1, tmp_path, DOMAIN)
    lines = write_manifest(tmp_path, problems).read_text().splitlines()
    assert lines[0] == "problem,path,layout_attempts,symbolically_solvable,plan_length"
    assert [line.split(",")[0] for line in lines[1:]] == ["random-000", "random-001"]
