from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from kitchen_tamp.cli.activity_planning import main
from tests.cli.interrupt import interrupt_once_printed
from tests.planning.conftest import DATA, KITCHEN, REPO

DOMAIN = str(KITCHEN / "domain.pddl")


def run_main(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def write(tmp_path: Path, text: str, name: str = "problem.pddl") -> str:
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_default_prints_numbered_bfs_and_ehc_plans(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_main(capsys)
    assert code == 0
    assert "BFS plan" in out and "EHC plan" in out
    assert "1. open drawer" in out
    assert "length 5" in out and "expanded" in out


def test_bare_problem_name_is_found_from_any_directory(tmp_path: Path) -> None:
    script = REPO / "pddl" / "activity_planning.py"
    for cwd in (REPO, REPO / "pddl", tmp_path):
        result = subprocess.run([sys.executable, str(script), "problem_hard.pddl"], cwd=cwd,
                                capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
        assert "7. placeOn spam stove" in result.stdout


def test_plan_out_writes_the_last_planner_in_ipc_form(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    out_file = tmp_path / "sub" / "kitchen.plan"
    code, _, _ = run_main(capsys, "problem_hard.pddl", "--planner", "ehc", "--planner", "astar",
                          "--plan-out", str(out_file))
    assert code == 0
    steps = [line for line in out_file.read_text().splitlines() if not line.startswith(";")]
    assert steps[0] == "(open drawer)" and len(steps) == 7


def test_json_output_is_one_document_with_every_planner(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_main(capsys, "--planner", "all", "--json")
    assert code == 0
    document = json.loads(out)
    assert [r["planner"] for r in document["results"]] == ["bfs", "ehc", "gbfs", "astar"]
    assert all(r["status"] == "solved" and r["length"] == 5 for r in document["results"]
               if r["planner"] in ("bfs", "astar"))


def test_unsolvable_problem_exits_1_and_says_so(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_main(capsys, str(DATA / "delivery_unsolvable.pddl"), "--domain",
                            str(DATA / "delivery_domain.pddl"), "--planner", "bfs")
    assert code == 1
    assert "unsolvable: none of the 8 reachable states" in err


def test_ehc_dead_end_exits_1(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    plan_file = tmp_path / "x.plan"
    code, _, err = run_main(capsys, str(DATA / "dead_end_problem.pddl"), "--domain",
                            str(DATA / "dead_end_domain.pddl"), "--planner", "ehc",
                            "--plan-out", str(plan_file))
    assert code == 1 and "dead end" in err
    assert not plan_file.exists()


def test_timeout_exhausted_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_main(capsys, "--planner", "bfs", "--timeout", "1e-9")
    assert code in (0, 1)  # a tiny problem may still finish within the first check
    if code == 1:
        assert "budget" in err


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("(define (problem p) (:domain kitchen) (:objects sugar - box) (:init (armClear)"
         " (:goal (holding sugar)))", "problem.pddl:1:"),
        ("(define (problem p) (:domain kitchen) (:objects sugar - box)\n"
         " (:init (armClear))\n (:goal (flying sugar)))", "problem.pddl:3:10: problem :goal uses "
                                                          "undefined predicate 'flying'"),
        ("(define (problem p) (:domain kitchen) (:objects sugar - box)\n"
         " (:init (armClear) (holding salt)) (:goal (holding sugar)))",
         "problem.pddl:2:29: problem :init uses undeclared object 'salt'"),
        ("(define (problem p) (:domain kitchen) (:objects sugar - box)\n"
         " (:init (armClear sugar)) (:goal (holding sugar)))",
         "predicate 'armClear' takes 0 arguments, got 1"),
        ("(define (problem p) (:domain bakery) (:objects sugar - box)"
         " (:init (armClear)) (:goal (holding sugar)))", "problem is for domain 'bakery'"),
        ("(define (problem p) (:domain kitchen) (:objects sugar - crate)"
         " (:init (armClear)) (:goal (holding sugar)))", "undeclared type 'crate'"),
        ("", "problem syntax error"),
    ],
)
def test_bad_problem_gives_one_line_and_exit_2(
        capsys: pytest.CaptureFixture[str], tmp_path: Path, text: str, expected: str) -> None:
    code, out, err = run_main(capsys, write(tmp_path, text), "--domain", DOMAIN)
    assert code == 2
    assert expected in err
    assert len(err.strip().splitlines()) == 1
    assert "Traceback" not in out + err


def test_bad_domain_names_the_undeclared_variable(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    domain = (KITCHEN / "domain.pddl").read_text().replace(
        ":precondition (and (boxOn ?b ?s) (armClear))", ":precondition (and (boxOn ?b ?x) (armClear))")
    domain_file = write(tmp_path, domain, "domain.pddl")
    code, _, err = run_main(capsys, str(KITCHEN / "problem.pddl"), "--domain", domain_file)
    assert code == 2
    assert "domain.pddl:" in err and "action 'pickUp' uses undeclared variable '?x'" in err


def test_missing_files_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_main(capsys, "no/such/file.pddl")
    assert code == 2 and "problem file not found" in err
    code, _, err = run_main(capsys, "--domain", "nowhere.pddl")
    assert code == 2 and "domain file not found" in err


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["--timeout", "abc"], "argument --timeout: not a number of seconds: 'abc'"),
        (["--timeout", "-1"], "argument --timeout: must be a positive number of seconds, got '-1'"),
        (["--timeout", "nan"], "argument --timeout: must be a positive number of seconds"),
        (["--planner", "dijkstra"], "argument --planner: invalid choice: 'dijkstra'"),
        (["--fast"], "unrecognized arguments: --fast"),
        (["--domain"], "argument --domain: expected one argument"),
        (["a.pddl", "b.pddl"], "unrecognized arguments: b.pddl"),
    ],
)
def test_a_command_line_mistake_is_one_line_naming_the_option_and_exit_2(
        capsys: pytest.CaptureFixture[str], argv: list[str], named: str) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {named}")
    assert lines[0].endswith("(see activity_planning.py --help)")  # the usage stays in --help


def test_help_shows_the_usage_and_every_option(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["--help"])
    assert exit_info.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: activity_planning.py")
    for option in ("--domain", "--planner", "--plan-out", "--json", "--timeout", "bfs,ehc,gbfs,astar,all"):
        assert option in out


def test_abbreviations_and_equals_forms_are_read(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_main(capsys, "--dom", DOMAIN, "--planner=bfs", "--tim", "30",
                            str(KITCHEN / "problem_hard.pddl"))
    assert code == 0 and "BFS plan" in out and "EHC plan" not in out and "length 7" in out


def test_the_planner_cli_imports_no_numpy_pybullet_or_drake(tmp_path: Path) -> None:
    # A fresh interpreter: this test process has numpy loaded by other tests.
    probe = (
        "import sys\n"
        "from kitchen_tamp.cli.activity_planning import main\n"
        "code = main(['problem_hard.pddl', '--planner', 'all', '--plan-out', sys.argv[1]])\n"
        "heavy = sorted(m for m in sys.modules if m.split('.')[0] in {'numpy', 'pybullet', 'pydrake'})\n"
        "print('heavy modules:', heavy)\n"
        "sys.exit(code)\n")
    result = subprocess.run([sys.executable, "-c", probe, str(tmp_path / "plan.txt")],
                            cwd=REPO, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "7. placeOn spam stove" in result.stdout
    assert "heavy modules: []" in result.stdout


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="threads are counted in /proc/self/status")
@pytest.mark.parametrize("preset", [None, "2"])
def test_the_planner_keeps_numpy_to_one_blas_thread_unless_told(preset: str | None) -> None:
    # numpy, once the planner has run (its compiled search imports it), starts no spinning BLAS
    # threads: the process has one thread; a user's own OPENBLAS_NUM_THREADS is kept.
    probe = (
        "from kitchen_tamp.cli.activity_planning import main\n"
        "main(['problem_hard.pddl', '--planner', 'gbfs'])\n"
        "import numpy\n"
        "threads = [l for l in open('/proc/self/status') if l.startswith('Threads:')][0].split()[1]\n"
        "print('threads', threads)\n")
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if preset is not None:
        env["OPENBLAS_NUM_THREADS"] = preset
    result = subprocess.run([sys.executable, "-c", probe], cwd=REPO, capture_output=True, text=True, env=env)
    assert result.returncode == 0, result.stderr
    assert f"threads {1 if preset is None else min(int(preset), os.cpu_count() or 1)}" in result.stdout


@pytest.mark.parametrize("where", ["under a file", "a folder"])
def test_an_unwritable_plan_out_is_refused_before_planning(
        capsys: pytest.CaptureFixture[str], tmp_path: Path, where: str) -> None:
    blocker = tmp_path / "notes.txt"
    blocker.write_text("not a folder")
    plan_out = blocker / "kitchen.plan" if where == "under a file" else tmp_path
    code, out, err = run_main(capsys, "--plan-out", str(plan_out))
    assert code == 2 and out == ""  # nothing was planned
    expected = f"{blocker} is a file, not a folder" if where == "under a file" else "is a folder, not a file"
    assert err.strip().splitlines() == [f"error: --plan-out {plan_out}: {expected}"]


SWITCHES_DOMAIN = """(define (domain switches) (:requirements :strips :typing) (:types switch)
  (:predicates (on ?s - switch) (off ?s - switch))
  (:action turn-on :parameters (?s - switch)
    :precondition (off ?s) :effect (and (on ?s) (not (off ?s))))
  (:action turn-off :parameters (?s - switch)
    :precondition (on ?s) :effect (and (off ?s) (not (on ?s)))))"""


@pytest.mark.slow
def test_ctrl_c_says_interrupted_and_exits_130(tmp_path: Path) -> None:
    switches = [f"s{i}" for i in range(24)]  # breadth-first search meets 2^24 states before the goal
    domain = write(tmp_path, SWITCHES_DOMAIN, "domain.pddl")
    problem = write(tmp_path, f"""(define (problem all-on) (:domain switches)
      (:objects {' '.join(switches)} - switch)
      (:init {' '.join(f'(off {s})' for s in switches)})
      (:goal (and {' '.join(f'(on {s})' for s in switches)})))""")
    args = [problem, "--domain", domain, "--planner", "bfs", "--timeout", "120"]
    run = interrupt_once_printed("pddl/activity_planning.py", args, line_prefix="problem all-on")
    assert run.returncode == 130, run.stderr
    assert run.stderr.strip().splitlines() == ["interrupted"]
    assert "BFS plan" not in run.stdout


def test_a_run_on_files_the_fast_reader_takes_loads_no_parser(tmp_path: Path) -> None:
    # The first run reads the kitchen with the fast reader (and stores the task), the second loads the
    # task cache: neither needs Lark or the pddl package (about 75 ms of start-up), nor anything heavy.
    probe = (
        "import sys\n"
        "from kitchen_tamp.cli.activity_planning import main\n"
        "code = main(['problem_hard.pddl', '--planner', 'bfs', '--timeout', '60'])\n"
        "avoidable = {'lark', 'pddl', 'numpy', 'pybullet', 'pydrake'}\n"
        "print('avoidable modules:', sorted({m.split('.')[0] for m in sys.modules} & avoidable))\n"
        "sys.exit(code)\n")
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}
    runs = [subprocess.run([sys.executable, "-c", probe], cwd=tmp_path, capture_output=True, text=True,
                           env=env) for _ in range(2)]
    for run in runs:
        assert run.returncode == 0, run.stderr
        assert "7. placeOn spam stove" in run.stdout
        assert "avoidable modules: []" in run.stdout, run.stdout
    assert len(list((tmp_path / "cache" / "kitchen_tamp" / "tasks").iterdir())) == 1


def test_a_file_the_fast_reader_leaves_is_read_by_the_pddl_package(tmp_path: Path) -> None:
    # ':requirements :adl' is outside the fast reader's fragment: the pddl package reads the file.
    domain = (KITCHEN / "domain.pddl").read_text()
    assert ":requirements" in domain
    (tmp_path / "domain.pddl").write_text(domain.replace(":requirements", ":requirements :adl", 1))
    (tmp_path / "problem.pddl").write_text((KITCHEN / "problem.pddl").read_text())
    probe = (
        "import sys\n"
        "from kitchen_tamp.cli.activity_planning import main\n"
        "code = main(['problem.pddl', '--planner', 'bfs'])\n"
        "print('parser loaded:', 'pddl' in sys.modules and 'lark' in sys.modules)\n"
        "sys.exit(code)\n")
    run = subprocess.run([sys.executable, "-c", probe], cwd=tmp_path, capture_output=True, text=True,
                         env={**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")})
    assert run.returncode == 0, run.stderr
    assert "length 5" in run.stdout and "parser loaded: True" in run.stdout
