from __future__ import annotations

import pytest

from kitchen_tamp.planning import load_task, parse_plan_text, plan, plan_text, validate_plan
from tests.planning.conftest import KITCHEN


@pytest.fixture
def kitchen():  # type: ignore[no-untyped-def]
    return load_task(KITCHEN / "problem.pddl")


def test_a_plan_round_trips_through_the_ipc_text_form(kitchen) -> None:  # type: ignore[no-untyped-def]
    found = plan(kitchen, "bfs").plan
    assert found is not None
    text = plan_text(found)
    assert text.splitlines()[0] == "(open drawer)"
    assert validate_plan(kitchen, parse_plan_text(text)).valid


def test_an_inapplicable_step_is_named_with_its_missing_precondition(kitchen) -> None:  # type: ignore[no-untyped-def]
    steps = [("pickUp", ("spam", "countertop")), ("placeIn", ("spam", "drawer"))]
    result = validate_plan(kitchen, steps)
    assert not result.valid and result.failed_step == 2
    assert "(opened drawer)" in result.message


def test_a_plan_that_stops_short_names_the_unmet_goal(kitchen) -> None:  # type: ignore[no-untyped-def]
    result = validate_plan(kitchen, [("open", ("drawer",))])
    assert not result.valid
    assert "(boxIn spam drawer)" in result.message


def test_unknown_actions_and_objects_are_reported(kitchen) -> None:  # type: ignore[no-untyped-def]
    assert "unknown action" in validate_plan(kitchen, [("fly", ("drawer",))]).message
    assert "unknown object" in validate_plan(kitchen, [("open", ("oven",))]).message


def test_plan_text_parser_rejects_garbage() -> None:
    with pytest.raises(ValueError, match="line 2"):
        parse_plan_text("(open drawer)\nopen drawer\n")
