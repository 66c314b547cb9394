"""python -m kitchen_tamp.evaluate end to end: fake runs for crashes, timeouts, interruption and
resume; real kitchen runs for the table's contents, locally and on a local Ray instance."""

from __future__ import annotations

import importlib.util
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from kitchen_tamp.evaluate.command_line import main
from kitchen_tamp.evaluate.results_table import PHASES, read_rows

FAKE_RUN = Path(__file__).resolve().parent / "fake_final_project.py"
FAKE_COMMAND = f"{sys.executable} {FAKE_RUN}"
TIMING_COLUMNS = {"wall_s", "run_dir", *PHASES}


def _fake_sweep(out: Path, seeds: str, *extra: str) -> list[str]:
    return ["--problems", "problem.pddl", "--seeds", seeds, "--out", str(out), "--run-command", FAKE_COMMAND,
            "--workers", "2", *extra]


def _by_seed(out: Path) -> dict[str, dict[str, str]]:
    return {row["seed"]: row for row in read_rows(out / "results.csv")}


@pytest.mark.slow
def test_crashes_timeouts_and_failures_are_recorded_and_the_sweep_goes_on(tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    assert main(_fake_sweep(out, "0-3", "--timeout", "3")) == 0
    rows = _by_seed(out)
    assert {seed: row["status"] for seed, row in rows.items()} == {
        "0": "solved", "1": "crashed", "2": "timeout", "3": "failed"}
    assert rows["1"]["failure_reason"] == "RuntimeError: fake crash"
    assert rows["1"]["exit_code"] == "3"
    assert rows["3"]["failure_stage"] == "refinement"
    summary = (out / "summary.md").read_text()
    assert "| problem | rrt | 1/4 | 25% [5, 70] |" in summary
    assert "crashed 1" in summary and "timeout 1" in summary and "refinement 1" in summary
    for plot in ("success.png", "time_cdf.png", "phase_times.png"):
        assert (out / plot).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "--run-command" in summary  # the command that made the sweep


@pytest.mark.slow
def test_an_interrupted_sweep_resumes_without_lost_or_repeated_rows(tmp_path: Path) -> None:
    out, log = tmp_path / "sweep", tmp_path / "calls.txt"
    command = [sys.executable, "-m", "kitchen_tamp.evaluate", *_fake_sweep(out, "0,4-6", "--workers", "1")]
    env = {**os.environ, "FAKE_RUN_LOG": str(log), "FAKE_RUN_SLEEP_S": "30"}
    sweep = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while len(read_rows(out / "results.csv")) < 1 and time.monotonic() < deadline:
        time.sleep(0.2)
    while "problem rrt 4" not in (log.read_text() if log.exists() else "") and time.monotonic() < deadline:
        time.sleep(0.2)
    sweep.send_signal(signal.SIGINT)
    _, stderr = sweep.communicate(timeout=60)
    assert sweep.returncode == 130, stderr
    assert "rerun with --resume" in stderr
    assert list(_by_seed(out)) == ["0"]

    env["FAKE_RUN_SLEEP_S"] = "0"
    assert subprocess.run([*command, "--resume"], env=env, capture_output=True).returncode == 0
    rows = read_rows(out / "results.csv")
    assert sorted(row["seed"] for row in rows) == ["0", "4", "5", "6"]
    assert all(row["status"] == "solved" for row in rows)
    calls = log.read_text().splitlines()
    assert calls.count("problem rrt 0") == 1  # finished before the interruption: not run again
    assert calls.count("problem rrt 4") == 2  # killed by the interruption, run again


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["--problems", "no_such_problem.pddl"], "problem file not found: no_such_problem.pddl"),
        (["--seeds", "5-2"], "bad seed range"),
        (["--workers", "0"], "--workers must be at least 1"),
        (["--timeout", "0"], "--timeout must be positive"),
    ],
)
def test_a_sweep_that_cannot_run_says_why_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], arguments: list[str], message: str
) -> None:
    assert main(["--out", str(tmp_path / "sweep"), *arguments]) == 2
    error = capsys.readouterr().err.strip()
    assert message in error and "\n" not in error


def test_an_unwritable_or_used_sweep_folder_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    assert main(_fake_sweep(blocker / "sweep", "0")) == 2
    assert "cannot write to the sweep folder" in capsys.readouterr().err
    out = tmp_path / "sweep"
    assert main(_fake_sweep(out, "0")) == 0
    before = (out / "results.csv").read_text()
    assert main(_fake_sweep(out, "0")) == 2
    assert "pass --resume" in capsys.readouterr().err
    assert (out / "results.csv").read_text() == before


def _comparable(row: dict[str, str]) -> dict[str, str]:
    return {k: v for k, v in row.items() if k not in TIMING_COLUMNS}


@pytest.fixture(scope="module")
def real_sweep(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """problem.pddl x rrt x seeds 0-1 with the real final_project.py, 2 workers."""
    out = tmp_path_factory.mktemp("real") / "sweep"
    assert main(["--problems", "problem.pddl", "--modes", "rrt", "--seeds", "0-1", "--workers", "2",
                 "--out", str(out)]) == 0
    return out


@pytest.mark.slow
def test_a_real_sweep_writes_verified_rows_and_their_summary(real_sweep: Path) -> None:
    rows = _by_seed(real_sweep)
    assert sorted(rows) == ["0", "1"]
    for row in rows.values():
        assert (row["status"], row["solved"], row["verified"], row["collision_free"]) == (
            "solved", "true", "true", "true")
        assert row["plan_length"] == "5"  # the shortest plan of problem.pddl
        assert float(row["path_length_rad"]) > 0.0 and float(row["total_s"]) > 0.0
        assert (Path(row["run_dir"]) / "report.json").exists()
    assert "| problem | rrt | 2/2 | 100% [34, 100] |" in (real_sweep / "summary.md").read_text()


@pytest.mark.slow
def test_ray_local_gives_the_same_rows_apart_from_timing(real_sweep: Path, tmp_path: Path) -> None:
    if importlib.util.find_spec("ray") is None:
        pytest.skip("ray is not installed (pip install '.[cluster]')")
    out = tmp_path / "ray"
    assert main(["--problems", "problem.pddl", "--modes", "rrt", "--seeds", "0", "--workers", "1",
                 "--ray", "local", "--out", str(out)]) == 0
    [ray_row] = read_rows(out / "results.csv")
    assert _comparable(ray_row) == _comparable(_by_seed(real_sweep)["0"])


def test_a_problem_of_another_kitchen_is_swept_with_the_domain_a_run_finds(tmp_path: Path) -> None:
    """The galley ships no domain.pddl of its own: without --domain, the sweep checks its
    problems against the shipped domain, as final_project.py does, instead of refusing them."""
    galley = Path(__file__).resolve().parents[2] / "src" / "kitchen_tamp" / "shipped_kitchens" / "galley"
    assert not (galley / "domain.pddl").exists()
    out = tmp_path / "sweep"
    assert main(["--problems", str(galley / "problem_swap.pddl"), "--seeds", "0", "--out", str(out),
                 "--run-command", FAKE_COMMAND]) == 0
    assert [row["status"] for row in read_rows(out / "results.csv")] == ["solved"]


def test_the_benchmarks_set_is_swept_under_its_names(tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    assert main(["--problem-set", "benchmarks", "--seeds", "0", "--out", str(out),
                 "--run-command", FAKE_COMMAND, "--workers", "2"]) == 0
    rows = read_rows(out / "results.csv")
    assert len(rows) == 8 and {row["problem"] for row in rows} >= {"nonmonotonic", "towers-sussman"}
    assert all(row["facts_learned"] == "0" for row in rows)


def test_a_problem_whose_binding_is_bad_stops_the_sweep_before_it_starts(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    towers = Path(__file__).resolve().parents[2] / "src" / "kitchen_tamp" / "shipped_kitchens" / "benchmarks"
    for name in ("domain.pddl", "towers/scene.toml", "towers/problem_sussman.pddl"):
        (tmp_path / Path(name).name).write_text((towers / name).read_text())
    binding = (towers / "domain.binding.toml").read_text()
    (tmp_path / "domain.binding.toml").write_text(binding[:binding.index("[actions.cook]")])
    assert main(["--problems", str(tmp_path / "problem_sussman.pddl"), "--out", str(tmp_path / "sweep"),
                 "--run-command", FAKE_COMMAND]) == 2
    error = capsys.readouterr().err.strip()
    assert error.endswith("actions.cook: the domain's action 'cook' has no skill binding")
    assert "\n" not in error
