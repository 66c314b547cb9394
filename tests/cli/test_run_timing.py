"""A run accounts for its seconds: ``timing`` counts from the process's start and its phases add
up to ``total_s``; ``--profile`` writes a profile of the run; installing compiles the kernels
without writing into the user's cache."""

from __future__ import annotations

import json
import marshal
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from kitchen_tamp.cli import prepare
from kitchen_tamp.cli.run_clock import process_start, seconds_since_start
from kitchen_tamp.execute.run_report import PHASES

REPO = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not Path("/proc/self/stat").is_file(), reason="needs /proc to know when a process began")
def test_the_clock_starts_when_the_process_did() -> None:
    code = "from kitchen_tamp.cli.run_clock import seconds_since_start as s; print(s())"
    clock = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", "import time; time.sleep(0.3); " + code],
                          capture_output=True, text=True, check=True)
    waited = time.perf_counter() - clock
    assert 0.3 <= float(done.stdout) <= waited + 0.02  # from exec, before Python loaded anything
    since = seconds_since_start()
    assert since is not None and process_start() <= time.perf_counter() - since + 0.02


@pytest.mark.slow
def test_the_phases_add_up_and_the_profile_is_written(tmp_path: Path) -> None:
    out = tmp_path / "run"
    clock = time.perf_counter()
    command = [sys.executable, "final_project.py", "rrt", "--no-video", "--no-physics", "--profile",
               "--out", str(out)]
    done = subprocess.run(command, cwd=REPO, capture_output=True, text=True)
    wall = time.perf_counter() - clock
    assert done.returncode == 0, done.stderr[-2000:]
    timing = json.loads((out / "report.json").read_text())["timing"]
    assert timing["total_s"] <= wall
    assert sum(timing[phase] for phase in PHASES if phase in timing) + timing["other_s"] == pytest.approx(
        timing["total_s"], abs=1e-3)
    assert 0.0 <= timing["other_s"] < 0.25 * timing["total_s"]
    assert timing["startup_s"] > 0.2  # the imports are in it
    stats = marshal.loads((out / "profile.prof").read_bytes())
    assert any(name == "run_plan" for (_, _, name) in stats)
    assert "Inclusive time" in (out / "profile.txt").read_text()


def test_preparing_leaves_the_user_cache_empty(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert prepare.main() == 0
    assert os.environ["XDG_CACHE_HOME"] == str(tmp_path)
    assert list(tmp_path.iterdir()) == []


COMPILES = """
from numba.core import event
from kitchen_tamp.cli import prepare
with event.install_recorder("numba:compile") as recorder:
    prepare._compile_kernels()
print(sorted({str(e.data["dispatcher"].py_func.__qualname__) for _, e in recorder.buffer if e.is_start}))
"""


@pytest.mark.slow
def test_a_second_process_compiles_no_kernel(tmp_path: Path) -> None:
    """Every compiled function a run calls comes from numba's cache once one process made it: one
    left out (e.g. the constructor numba makes for a structref's Python class) costs seconds a run."""
    environment = {**os.environ, "XDG_CACHE_HOME": str(tmp_path)}
    for _ in range(2):
        done = subprocess.run([sys.executable, "-c", COMPILES], cwd=REPO, env=environment,
                              capture_output=True, text=True)
        assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip().splitlines()[-1] == "[]"
