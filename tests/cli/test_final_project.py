"""final_project.py end to end on the kitchen problems, headless: verified runs, the files
they leave, determinism, replay (against the files the run recorded or the ones named, with
their digests), a plan of no actions, and every exit code."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kitchen_tamp.cli import final_project
from kitchen_tamp.cli.final_project import main
from kitchen_tamp.refinement import MotionSolution
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from tests.cli.interrupt import interrupt_once_printed
from tests.conftest import KitchenRuns

REPO = Path(__file__).resolve().parents[2]


def _report(run_dir: Path, name: str = "report.json") -> dict[str, Any]:
    data: dict[str, Any] = json.loads((run_dir / name).read_text())
    return data


def _without_timing(report: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in report.items() if k != "timing"}


@pytest.fixture(scope="module")
def hard_run(kitchen_runs: KitchenRuns) -> Path:
    """problem_hard.pddl with rrt, seed 1, with the GIF (planned once per session)."""
    return kitchen_runs.run_dir("problem_hard.pddl", "rrt", 1, video=True)


@pytest.mark.slow
def test_hard_problem_is_solved_verified_and_leaves_every_file(hard_run: Path) -> None:
    report = _report(hard_run)
    assert report["solved"] is True and report["failure"] is None
    assert report["plan"] is not None and len(report["plan"]) == 7
    assert any(a.startswith("(placeIn") for a in report["plan"])  # the drawer is the temporary place
    verification = report["verification"]
    assert verification["collision_free"] is True
    assert verification["goal_atoms"] == {"(boxOn spam stove)": True, "(boxOn sugar countertop)": True}
    assert verification["resolution_rad"] <= 0.005
    assert [s["action"] for s in report["steps"]] == report["plan"]
    assert all(s["solved"] and s["planner"] == "rrt_connect" for s in report["steps"])
    assert {
        "startup_s",
        "symbolic_s",
        "skills_s",
        "motion_s",
        "verification_s",
        "rendering_s",
        "total_s",
    } <= set(report["timing"])
    import imageio.v3 as iio

    frames = iio.imread(hard_run / "replay.gif", index=None)
    assert len(frames) >= 20
    assert not np.array_equal(frames[0], frames[-1])  # the scene changed
    assert (hard_run / "joints.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert report["outputs"]["html"] == "replay.html" and (hard_run / "replay.html").stat().st_size > 1e6
    assert report["outputs"]["html_shows"] == "physics"  # the motion the simulator executed


@pytest.mark.slow
def test_replay_reproduces_the_verification(hard_run: Path, tmp_path: Path) -> None:
    assert main(["replay", str(hard_run), "--out", str(tmp_path), "--no-video"]) == 0
    replayed = _report(tmp_path, "replay_report.json")
    assert replayed["verification"] == _report(hard_run)["verification"]
    assert replayed["solved"] is True


@pytest.mark.slow
def test_replay_of_a_tampered_trajectory_fails(hard_run: Path, tmp_path: Path) -> None:
    data = json.loads((hard_run / "trajectory.json").read_text())
    data["steps"] = data["steps"][:-1]  # the last placement never happens
    (tmp_path / "trajectory.json").write_text(json.dumps(data))
    assert main(["replay", str(tmp_path), "--no-video"]) == 1
    goals = _report(tmp_path, "replay_report.json")["verification"]["goal_atoms"]
    assert False in goals.values()


def _with_scene(hard_run: Path, folder: Path, scene: Path) -> Path:
    data = json.loads((hard_run / "trajectory.json").read_text())
    data["scene"] = str(scene)
    (folder / "trajectory.json").write_text(json.dumps(data))
    return folder


@pytest.mark.slow
def test_replay_judges_in_the_kitchen_the_run_recorded(
    hard_run: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from kitchen_tamp.shipped_kitchens import default_scene_path

    recorded = json.loads((hard_run / "trajectory.json").read_text())["scene"]
    assert Path(recorded).resolve() == default_scene_path().resolve()
    galley = REPO / "src" / "kitchen_tamp" / "shipped_kitchens" / "galley" / "scene.toml"
    capsys.readouterr()
    # the galley has no `drawer`: judged there, the problem itself is refused
    assert main(["replay", str(_with_scene(hard_run, tmp_path, galley)), "--no-video"]) == 2
    assert str(galley) in capsys.readouterr().err
    # --scene overrides what the file recorded
    assert main(["replay", str(tmp_path), "--no-video", "--scene", recorded]) == 0
    gone = tmp_path / "gone"
    gone.mkdir()
    assert main(["replay", str(_with_scene(hard_run, gone, gone / "scene.toml")), "--no-video"]) == 2
    assert "the scene file this run planned in is gone" in capsys.readouterr().err


def _weaker(problem: Path, folder: Path) -> Path:
    """``problem`` with only its first goal atom, in ``folder``."""
    text = problem.read_text()
    weak = folder / "weak.pddl"
    weak.write_text(text.replace("(boxOn sugar countertop)\n    (boxIn spam drawer)", "(boxIn spam drawer)"))
    assert weak.read_text() != text
    return weak


@pytest.mark.slow
def test_replay_names_the_files_it_judges_against_and_whether_they_are_the_runs(
    kitchen_runs: KitchenRuns, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A copy that points at a weaker problem and stops early: judged against what it names it
    verifies, and the verdict line says which problem that was and that it is not the one the
    run planned with; judged against the run's problem (``--problem``) it is refused."""
    run = kitchen_runs.run_dir("problem.pddl", "rrt", 0)
    report = _report(run)
    assert report["inputs"]["problem"]["matches_run"] is True and report["scene_path"]
    data = json.loads((run / "trajectory.json").read_text())
    recorded = data["sha256"]
    assert set(recorded) == {"problem", "domain", "scene"}
    original = Path(data["problem"])
    data["problem"] = str(_weaker(original, tmp_path))
    data["steps"] = data["steps"][:3]  # the sugar is never moved
    (tmp_path / "trajectory.json").write_text(json.dumps(data))
    capsys.readouterr()
    assert main(["replay", str(tmp_path), "--no-video", "--no-physics"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "judged against problem weak.pddl (DIFFERENT from the run's)" in last, last
    assert "domain domain.pddl (as planned)" in last and "scene scene.toml (as planned)" in last
    inputs = _report(tmp_path, "replay_report.json")["inputs"]
    assert inputs["problem"]["matches_run"] is False and inputs["problem"]["sha256"] != recorded["problem"]
    assert main(["replay", str(tmp_path), "--no-video", "--no-physics", "--problem", str(original)]) == 1
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert "NOT SOLVED (verification)" in last and "judged against problem problem.pddl (as planned)" in last


@pytest.mark.slow
def test_a_plan_of_no_actions_is_solved_and_verified_by_both_judges(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    problem = tmp_path / "already.pddl"
    text = (REPO / "pddl" / "problem.pddl").read_text()
    problem.write_text(text.replace("(boxOn sugar countertop)\n    (boxIn spam drawer)",
                                    "(boxOn sugar stove)\n    (boxOn spam countertop)"))
    domain = REPO / "pddl" / "domain.pddl"
    out = tmp_path / "run"
    assert main(["rrt", "--problem", str(problem), "--domain", str(domain), "--out", str(out)]) == 0
    report = _report(tmp_path / "run")
    assert report["plan"] == [] and report["solved"] is True
    assert report["verification"]["verified"] is True and report["physics"]["verified"] is True
    assert report["verification"]["min_clearance_m"] is None  # nothing moved, nothing measured
    assert "SOLVED and verified: 0 actions, collision-free (no motion)" in capsys.readouterr().out
    assert main(["replay", str(tmp_path / "run"), "--no-video"]) == 0


@pytest.mark.slow
def test_same_seed_gives_the_same_report_apart_from_timing(tmp_path: Path) -> None:
    a, b = tmp_path / "a", tmp_path / "b"
    for out in (a, b):
        assert main(["rrt", "--seed", "2", "--out", str(out), "--no-video"]) == 0
    assert _without_timing(_report(a)) == _without_timing(_report(b))
    assert (a / "trajectory.json").read_text() == (b / "trajectory.json").read_text()
    assert _report(a)["outputs"]["gif"] is None and not (a / "replay.gif").exists()


@pytest.mark.slow
def test_basic_rrt_solves_the_kitchen_problem(tmp_path: Path) -> None:
    assert main(["rrt", "--rrt", "basic", "--out", str(tmp_path), "--no-video"]) == 0
    report = _report(tmp_path)
    assert report["motion_planner"] == "rrt" and report["verification"]["collision_free"] is True


@pytest.mark.slow
def test_default_output_folder_is_named_after_problem_mode_and_seed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(final_project, "_motion_backend", lambda args: _FailingBackend())
    assert main(["rrt", "--seed", "4", "--no-video"]) == 1
    assert (tmp_path / "out" / "problem-rrt-seed4" / "report.json").exists()


class _FailingBackend:
    name = "never"

    def solve(self, *args: object) -> MotionSolution:
        return MotionSolution(None, "refused", 1, {"iterations": 0})


@pytest.mark.slow
def test_a_step_that_cannot_be_refined_exits_1_and_the_report_names_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(final_project, "_motion_backend", lambda args: _FailingBackend())
    argv = ["rrt", "--out", str(tmp_path), "--samples-per-step", "2", "--max-plans", "3"]
    assert main(argv) == 1
    report = _report(tmp_path)
    assert report["solved"] is False
    assert report["failure"]["stage"] == "refinement"
    assert report["failure"]["step"] == 1 and report["failure"]["action"] == "(open drawer)"
    bilevel = report["bilevel"]
    plans = bilevel["abstract_plans_tried"]
    assert 2 <= plans <= 3 and plans == len(bilevel["plans"])  # every plan starts by opening the drawer
    assert bilevel["samples"] == bilevel["failures"] == 2 * plans
    assert all(plan["steps"][0]["samples"] == 2 for plan in bilevel["plans"])
    most = f"most frequent failure ({2 * plans} of {2 * plans} failed samples): (open drawer): "
    assert most in report["failure"]["reason"], report["failure"]["reason"]
    out = capsys.readouterr().out
    assert "sample failed" in out and most in out.strip().splitlines()[-1]


def test_no_symbolic_plan_exits_1(tmp_path: Path) -> None:
    problem = tmp_path / "crowded.pddl"
    text = (REPO / "pddl" / "problem.pddl").read_text()
    goal = "(boxOn sugar countertop)\n    (boxIn spam drawer)"
    assert goal in text
    problem.write_text(
        text.replace(goal, "(boxOn sugar stove)\n    (boxOn spam stove)")
    )  # one box per surface
    code = main(
        [
            "rrt",
            "--problem",
            str(problem),
            "--domain",
            str(REPO / "pddl" / "domain.pddl"),
            "--out",
            str(tmp_path / "run"),
        ]
    )
    assert code == 1
    assert _report(tmp_path / "run")["failure"]["stage"] == "symbolic"


@pytest.mark.parametrize(
    "argv",
    [
        ["rrt", "--problem", "no/such/file.pddl"],
        ["optimizes", "--collision-model", "pybullet"],
        ["optimizes", "--waypoints", "1"],
        ["rrt", "--seed", "-1"],
        ["rrt", "--rrt", "prm"],
        ["replay", "no/such/run"],
        ["frobnicate"],
    ],
)
def test_bad_input_exits_2_with_one_line(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    try:
        code = main(argv)
    except SystemExit as exit_:  # argparse's usage errors
        code = int(exit_.code or 0)
    assert code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["rrt", "--seed", "abc"], "error: argument --seed: not an integer: 'abc' (see final_project.py rrt"),
        (["optimizes", "--waypoints", "1"], "argument --waypoints: must be at least 2, got 1"),
        (["rrt", "--frobnicate"], "unrecognized arguments: --frobnicate"),
        (["replay"], "the following arguments are required: RUN_DIR"),
    ],
)
def test_a_command_line_mistake_is_one_line_naming_the_option(
    argv: list[str], named: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and named in lines[0] and "--help" in lines[0], lines


def test_an_out_no_one_can_write_is_refused_at_once_even_for_root(capsys: pytest.CaptureFixture[str]) -> None:
    """Permission bits say nothing for root: the folder is made and probed before planning."""
    assert main(["rrt", "--out", "/proc/no/such/dir", "--no-video"]) == 2
    captured = capsys.readouterr()
    assert captured.err.strip().splitlines() == [
        "error: --out /proc/no/such/dir: cannot write there (No such file or directory)"]
    assert captured.out == ""  # nothing was planned


def test_gui_without_a_display_is_refused(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    assert main(["rrt", "--gui"]) == 2
    assert "display" in capsys.readouterr().err


@pytest.mark.slow
def test_planning_with_the_pybullet_model_is_verified_too(tmp_path: Path) -> None:
    assert main(["rrt", "--collision-model", "pybullet", "--out", str(tmp_path), "--no-video"]) == 0
    report = _report(tmp_path)
    assert {s["motion"]["collision_model"] for s in report["steps"]} == {"pybullet"}
    assert report["verification"]["collision_free"] is True


@pytest.mark.slow
def test_optimizes_solves_verifies_and_compares_with_rrt_connect(tmp_path: Path) -> None:
    assert main(["optimizes", "--out", str(tmp_path), "--no-video"]) == 0
    report = _report(tmp_path)
    assert report["solved"] is True and report["motion_planner"] == "trajectory_optimization"
    assert report["verification"]["collision_free"] is True
    for step in report["steps"]:
        motion = step["motion"]
        assert motion["solver"] in ("SNOPT", "IPOPT")
        assert motion["attempts"][-1]["dense_check"] == "free"
        assert motion["waypoints"] >= DEFAULT_SETTINGS.num_waypoints
        if motion["rrt_connect_path_length_rad"] is not None:
            assert motion["length_ratio_to_rrt_connect"] > 0.0
        else:  # the straight line was free and the answer: no reference was planned
            assert motion["attempts"][0]["initial_guess"] == "straight line"
        assert motion["path_length_rad"] >= 0.0
    assert "optimization_s" in report["timing"]["steps"][0]
    assert (tmp_path / "joints.png").exists()


@pytest.mark.slow
def test_step_waits_for_enter_before_each_action(
    hard_run: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    prompts: list[str] = []
    monkeypatch.setattr("builtins.input", lambda prompt="": prompts.append(prompt) or "")
    assert main(["replay", str(hard_run), "--out", str(tmp_path), "--no-video", "--step"]) == 0
    plan = _report(hard_run)["plan"]
    assert len(prompts) == len(plan)
    assert all(action in prompt for action, prompt in zip(plan, prompts, strict=True))


@pytest.mark.parametrize("mode", ["rrt", "replay"])
@pytest.mark.parametrize("where", ["under a file", "a file"])
def test_an_unwritable_out_is_refused_before_planning(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], mode: str, where: str
) -> None:
    blocker = tmp_path / "notes.txt"
    blocker.write_text("not a folder")
    out = blocker / "run" if where == "under a file" else blocker
    argv = ["rrt", "--out", str(out)] if mode == "rrt" else ["replay", str(tmp_path), "--out", str(out)]
    assert main(argv) == 2
    captured = capsys.readouterr()
    culprit = f"{blocker} " if where == "under a file" else ""
    assert captured.err.strip() == f"error: --out {out}: {culprit}is a file, not a folder"
    assert captured.out == ""  # nothing was planned or replayed
    assert blocker.read_text() == "not a folder"


def test_a_kitchen_model_that_does_not_match_the_map_is_a_setup_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from dataclasses import replace

    from kitchen_tamp.kitchen import default_kitchen_map
    from kitchen_tamp.kitchen.scene import choice as scene_choice

    kitchen_map = default_kitchen_map()
    urdf = kitchen_map.kitchen_urdf.read_text()
    assert urdf.count('"robot_mount"') >= 1
    renamed = tmp_path / "kitchen.urdf"
    renamed.write_text(urdf.replace('"robot_mount"', '"robot_stand"'))
    mismatched = replace(kitchen_map, kitchen_urdf=renamed)
    monkeypatch.setattr(scene_choice, "default_kitchen_map", lambda: mismatched)
    assert main(["rrt", "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.strip() == ("error: the kitchen's model files do not match its kitchen map: "
                           "body 'kitchen' has no link 'robot_mount'")


def test_no_nonlinear_solver_is_a_setup_error_found_before_planning(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from kitchen_tamp.motion.trajopt import solver

    def no_solver() -> None:
        raise solver.NoNonlinearSolverError("Drake has neither SNOPT nor IPOPT available")

    monkeypatch.setattr(solver, "nonlinear_solver", no_solver)
    assert main(["optimizes", "--out", str(tmp_path / "run")]) == 2
    captured = capsys.readouterr()
    assert captured.err.strip().splitlines() == [
        "error: optimizes needs a nonlinear solver: Drake has neither SNOPT nor IPOPT available; "
        "use rrt, or a Drake build that has one"]
    assert captured.out == "" and not (tmp_path / "run").exists()


@pytest.mark.slow
def test_ctrl_c_says_interrupted_and_exits_130(tmp_path: Path) -> None:
    out = tmp_path / "run"
    run = interrupt_once_printed("final_project.py", ["rrt", "--problem", "problem_hard.pddl", "--no-video",
                                                      "--out", str(out)], line_prefix="[plan 1, step 1]")
    assert run.returncode == 130, run.stderr
    assert run.stderr.strip().splitlines()[-1] == "interrupted"
    assert "Traceback" not in run.stderr and "SOLVED" not in run.stdout  # neither verdict
    assert not (out / "report.json").exists()
