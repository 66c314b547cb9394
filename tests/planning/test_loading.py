from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import PlanningInputError, load_task
from kitchen_tamp.planning.loading import clear_domain_cache, domain_model
from tests.planning.conftest import KITCHEN


def test_a_domain_is_translated_once_per_content(tmp_path: Path) -> None:
    domain = tmp_path / "domain.pddl"
    domain.write_text((KITCHEN / "domain.pddl").read_text())
    first = domain_model(domain)
    assert domain_model(domain) is first
    load_task(KITCHEN / "problem.pddl", domain)
    load_task(KITCHEN / "problem_hard.pddl", domain)
    assert domain_model(domain) is first
    domain.write_text((KITCHEN / "domain.pddl").read_text() + "\n; edited\n")
    assert domain_model(domain) is not first
    clear_domain_cache()
    assert domain_model(domain) is not first


def test_cached_and_fresh_loads_give_the_same_task() -> None:
    clear_domain_cache()
    fresh = load_task(KITCHEN / "problem_hard.pddl")
    cached = load_task(KITCHEN / "problem_hard.pddl")
    assert fresh == cached


def test_a_bad_domain_is_reported_on_every_load(tmp_path: Path) -> None:
    domain = tmp_path / "domain.pddl"
    domain.write_text((KITCHEN / "domain.pddl").read_text().replace(
        ":precondition (and (boxOn ?b ?s) (armClear))", ":precondition (and (boxOn ?b ?s) (armClar))"))
    for _ in range(2):
        with pytest.raises(PlanningInputError, match="undefined predicate 'armClar'"):
            load_task(KITCHEN / "problem.pddl", domain)
