"""A domain's binding: the shipped ones bind every action and predicate; each kind of mistake in
a binding file is one line naming the file and the key, and the command lines exit 2 on it."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

from kitchen_tamp.cli.final_project import main as final_project_main
from kitchen_tamp.kitchen import BindingFileError, read_binding
from kitchen_tamp.kitchen.binding import RELATIONS, SKILL_ROLES
from kitchen_tamp.kitchen.binding_reader import binding_path_for
from kitchen_tamp.kitchen.skills.registry import SKILLS
from kitchen_tamp.planning.loading import domain_model
from kitchen_tamp.shipped_kitchens import default_domain_path, kitchen_folder
from tests.kitchen.conftest import REPO

BENCHMARKS = kitchen_folder("benchmarks")
REGIONS_DOMAIN = BENCHMARKS / "domain.pddl"


def test_every_skill_of_the_binding_has_a_sampler() -> None:
    assert set(SKILLS) == set(SKILL_ROLES)


def test_the_seed_domain_binds_its_actions_to_the_skills_it_always_had() -> None:
    binding = read_binding(default_domain_path())
    skills = {name: b.skill for name, b in binding.actions.items()}
    assert skills == {"open": "open", "pickUp": "pick", "cabPickUp": "pick", "placeOn": "place",
                      "placeIn": "place_in"}
    assert dict(binding.actions["placeOn"].roles) == {"object": 0, "support": 1}
    assert binding.predicates["boxOn"] == ("on_surface",)
    assert binding.predicates["armClear"] == ("hand_empty",)


def test_a_symbolic_link_to_the_domain_finds_the_binding_beside_the_file() -> None:
    assert binding_path_for(REPO / "pddl" / "domain.pddl") == binding_path_for(default_domain_path())
    assert read_binding(BENCHMARKS / "towers" / "domain.pddl").path == binding_path_for(REGIONS_DOMAIN)


def test_the_regions_domain_binds_every_action_and_predicate() -> None:
    binding = read_binding(REGIONS_DOMAIN)
    model = domain_model(REGIONS_DOMAIN)
    assert set(binding.actions) == {a.name for a in model.actions}
    assert set(binding.predicates) == set(model.predicates)
    assert binding.predicates["on"] == ("on_surface", "on_region", "on_box")
    assert binding.actions["wash"].skill == "process"
    assert binding.pddl_type("region", "sink") == "sink" and binding.pddl_type("surface") == "region"
    assert all(r in RELATIONS for relations in binding.predicates.values() for r in relations)


def _copy(tmp_path: Path, edit: Callable[[str], str]) -> Path:
    """The seed's domain in ``tmp_path`` with its binding edited by ``edit``."""
    domain = tmp_path / "domain.pddl"
    shutil.copyfile(default_domain_path(), domain)
    text = binding_path_for(default_domain_path()).read_text()
    binding_path_for(domain).write_text(edit(text))
    return domain


MISTAKES: dict[str, tuple[Callable[[str], str], str, str]] = {
    "action without binding": (
        lambda t: t.replace('[actions.placeIn]\nskill = "place_in"\nobject = "?b"\ndrawer = "?o"\n', ""),
        "actions.placeIn", "the domain's action 'placeIn' has no skill binding",
    ),
    "unknown parameter": (
        lambda t: t.replace('object = "?b"\nsupport = "?s"', 'object = "?x"\nsupport = "?s"', 1),
        "actions.pickUp.object", "'?x' is not a parameter of pickUp (its parameters: ?b, ?s)",
    ),
    "unknown skill": (
        lambda t: t.replace('skill = "open"', 'skill = "yank"'),
        "actions.open.skill", "unknown skill 'yank'",
    ),
    "unknown role": (
        lambda t: t.replace('drawer = "?o"\n\n[actions.pickUp]', 'handle = "?o"\n\n[actions.pickUp]'),
        "actions.open.handle", "unknown key (roles of open: drawer)",
    ),
    "missing role": (
        lambda t: t.replace('skill = "open"\ndrawer = "?o"', 'skill = "open"'),
        "actions.open", "missing role 'drawer' of skill open",
    ),
    "action the domain lacks": (
        lambda t: t + '\n[actions.juggle]\nskill = "pick"\nobject = "?b"\n',
        "actions.juggle", "the domain has no action 'juggle'",
    ),
    "unknown relation": (
        lambda t: t.replace('boxOn = "on_surface"', 'boxOn = "on_top"'),
        "predicates.boxOn", "unknown relation 'on_top'",
    ),
    "relation of another arity": (
        lambda t: t.replace('boxOn = "on_surface"', 'boxOn = "opened"'),
        "predicates.boxOn", "opened relates 1 objects, the domain's boxOn takes 2",
    ),
    "predicate without meaning": (
        lambda t: t.replace('cabClear = "drawer_clear"\n', ""),
        "predicates", "missing predicate 'cabClear' of the domain",
    ),
    "type the domain lacks": (
        lambda t: t.replace('box = "box"', 'box = "item"'),
        "types.box", "the domain has no type 'item'",
    ),
    "not TOML": (lambda t: t + "\n[[[", "", "not valid TOML"),
}


@pytest.mark.parametrize("mistake", sorted(MISTAKES))
def test_a_bad_binding_names_the_file_and_key(tmp_path: Path, mistake: str) -> None:
    edit, key, message = MISTAKES[mistake]
    domain = _copy(tmp_path, edit)
    with pytest.raises(BindingFileError) as raised:
        read_binding(domain)
    assert raised.value.key == key
    assert message in str(raised.value)
    assert str(raised.value).startswith(str(binding_path_for(domain)))


def test_a_domain_without_a_binding_is_refused_naming_the_file(tmp_path: Path) -> None:
    domain = tmp_path / "domain.pddl"
    shutil.copyfile(default_domain_path(), domain)
    with pytest.raises(BindingFileError, match="no skill binding for domain 'kitchen'") as raised:
        read_binding(domain)
    assert str(raised.value).startswith(str(tmp_path / "domain.binding.toml"))


@pytest.mark.parametrize("mistake", ["action without binding", "unknown parameter"])
def test_the_command_line_exits_2_with_one_line(
    tmp_path: Path, mistake: str, capsys: pytest.CaptureFixture[str]
) -> None:
    domain = _copy(tmp_path, MISTAKES[mistake][0])
    code = final_project_main(["rrt", "--domain", str(domain), "--no-video", "--out", str(tmp_path / "run")])
    assert code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and MISTAKES[mistake][1] in err[0] and "Traceback" not in err[0]
