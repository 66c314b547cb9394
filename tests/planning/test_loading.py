from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.planning import PlanningInputError, load_task
from kitchen_tamp.planning.loading import clear_domain_cache, domain_model
from tests.planning.conftest import DATA, KITCHEN


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


def _shout_keywords(text: str) -> str:
    """``text`` with its keywords in mixed and upper case, as IPC files have them (``(Define``, ``:INIT``)."""
    for word in ("define", "domain", "problem", "and", "not"):
        text = text.replace(f"({word} ", f"({word.upper() if word != 'define' else 'Define'} ")
    for word in (":requirements", ":types", ":action", ":parameters", ":precondition", ":effect",
                 ":objects", ":init", ":goal", ":strips", ":typing", ":domain"):
        text = text.replace(word, word.upper())
    return text


def test_keywords_are_read_in_any_case(tmp_path: Path) -> None:
    domain, problem = tmp_path / "delivery_domain.pddl", tmp_path / "delivery_two_parcels.pddl"
    domain.write_text(_shout_keywords((DATA / "delivery_domain.pddl").read_text()))
    problem.write_text(_shout_keywords((DATA / "delivery_two_parcels.pddl").read_text()))
    assert "(Define (DOMAIN" in domain.read_text() and ":INIT" in problem.read_text()
    assert load_task(problem, domain) == load_task(DATA / "delivery_two_parcels.pddl",
                                                   DATA / "delivery_domain.pddl")


def test_an_error_in_a_file_with_upper_case_keywords_names_its_line_and_column(tmp_path: Path) -> None:
    domain, problem = tmp_path / "delivery_domain.pddl", tmp_path / "problem.pddl"
    domain.write_text((DATA / "delivery_domain.pddl").read_text())
    problem.write_text("(Define (PROBLEM p) (:DOMAIN delivery)\n  (:OBJECTS vw - van)\n"
                       "  (:INIT (AT vw nowhere))\n  (:GOAL (AT vw depot)))\n")
    with pytest.raises(PlanningInputError) as caught:
        load_task(problem, domain)
    assert "nowhere" in str(caught.value) and ":3:" in str(caught.value)
