"""results.csv: rows from task results, streamed, and read back after an interruption."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from kitchen_tamp.evaluate.grid import TaskSpec
from kitchen_tamp.evaluate.results_table import (
    COLUMNS,
    ResultsTable,
    ResultsTableError,
    read_rows,
    row_of,
    status_of,
)
from kitchen_tamp.evaluate.task_run import TaskResult

from .fake_final_project import report


def _result(seed: int, exit_code: int | None, data: dict[str, Any] | None, timed_out: bool = False,
            stderr: str = "") -> TaskResult:
    task = TaskSpec(Path("/p/problem.pddl"), "rrt", seed)
    return TaskResult(task, exit_code, timed_out, 3.5, data, stderr, Path("/runs") / task.task_id)


def test_statuses_follow_exit_code_and_report() -> None:
    solved = report("problem.pddl", "rrt", 0, True)
    assert status_of(_result(0, 0, solved)) == "solved"
    assert status_of(_result(0, 1, report("problem.pddl", "rrt", 0, False))) == "failed"
    assert status_of(_result(0, None, None, timed_out=True)) == "timeout"
    assert status_of(_result(0, 3, None)) == "crashed"
    assert status_of(_result(0, -9, solved)) == "crashed"
    assert status_of(_result(0, 0, None)) == "crashed"  # exit 0 but no report
    assert status_of(_result(0, 2, None)) == "bad_input"


def test_row_takes_verdicts_counts_and_times_from_the_report() -> None:
    row = row_of(_result(4, 0, report("problem.pddl", "rrt", 4, True)))
    assert set(row) == set(COLUMNS)
    assert row["task_id"] == "problem-rrt-seed4"
    verdicts = (row["status"], row["solved"], row["verified"], row["collision_free"])
    assert verdicts == ("solved", "true", "true", "true")
    assert row["physics_verified"] == ""  # no physics section: left empty
    assert (row["plan_length"], row["samples"], row["backtracks"]) == ("2", "6", "4")
    assert float(row["path_length_rad"]) == pytest.approx(1.75)
    assert (row["startup_s"], row["total_s"], row["verification_s"]) == ("0.5000", "2.0000", "")
    assert (row["failure_stage"], row["failure_reason"]) == ("", "")


def test_row_reads_a_physics_verdict_when_the_report_has_one() -> None:
    data = report("problem.pddl", "rrt", 0, True)
    data["physics"] = {"verified": False}
    assert row_of(_result(0, 0, data))["physics_verified"] == "false"


def test_failures_name_their_cause() -> None:
    failed = row_of(_result(3, 1, report("problem.pddl", "rrt", 3, False)))
    assert (failed["failure_stage"], failed["failure_reason"]) == ("refinement", "SeSamE: out of samples")
    crashed = row_of(_result(1, 3, None, stderr="Traceback ...\n  boom\nRuntimeError: fake crash"))
    assert (crashed["status"], crashed["failure_stage"]) == ("crashed", "crashed")
    assert crashed["failure_reason"] == "RuntimeError: fake crash"
    timeout = row_of(_result(2, None, None, timed_out=True))
    assert (timeout["status"], timeout["exit_code"], timeout["solved"]) == ("timeout", "", "false")


def test_a_row_cut_off_by_an_interruption_is_dropped_and_rows_are_never_duplicated(tmp_path: Path) -> None:
    path = tmp_path / "results.csv"
    rows = [row_of(_result(seed, 0, report("problem.pddl", "rrt", seed, True))) for seed in (0, 4, 5)]
    with ResultsTable(path, resume=False) as table:
        for row in rows:
            table.append(row)
        table.append(rows[0])  # a second row for one task is not written
    text = path.read_text()
    assert len(read_rows(path)) == 3
    path.write_text(text[: len(text) - 20])  # the last row cut off mid-write
    assert [r["task_id"] for r in read_rows(path)] == ["problem-rrt-seed0", "problem-rrt-seed4"]
    with ResultsTable(path, resume=True) as table:
        assert table.task_ids == {"problem-rrt-seed0", "problem-rrt-seed4"}
        table.append(rows[2])
    assert read_rows(path) == rows


def test_starting_without_resume_empties_the_table(tmp_path: Path) -> None:
    path = tmp_path / "results.csv"
    with ResultsTable(path, resume=False) as table:
        table.append(row_of(_result(0, 0, report("problem.pddl", "rrt", 0, True))))
    with ResultsTable(path, resume=False) as table:
        assert table.task_ids == set()
    assert read_rows(path) == []


def test_a_table_of_other_columns_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "results.csv"
    path.write_text("a,b\n1,2\n")
    with pytest.raises(ResultsTableError, match="not a results table"):
        read_rows(path)
