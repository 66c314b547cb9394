"""A wheel built from the checkout, installed into a fresh virtual environment outside it, runs
the kitchen from an empty folder: everything it needs (scene, domain, problems) is package data."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from kitchen_tamp.motion.geometry.spheres import sphere_cache_directory
from tests.kitchen.conftest import REPO

pytestmark = pytest.mark.slow


def _run(
    command: list[str], cwd: Path, env: dict[str, str], timeout: float = 600
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)


def _clean_environment(cache: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}
    env["XDG_CACHE_HOME"] = str(cache)
    return env


def _reuse_generated_spheres(cache: Path) -> None:
    """Copy the sphere sets and pair tables this machine already generated into the fresh cache:
    they are keyed by what they were generated from, so they are the ones the wheel would generate
    again (a fresh machine spends a couple of minutes on them; the suite should pay that once)."""
    spheres = sphere_cache_directory()
    if spheres.is_dir():
        shutil.copytree(spheres, cache / "kitchen_tamp" / "spheres")


def test_wheel_installs_and_runs_from_an_empty_folder(tmp_path: Path) -> None:
    source = tmp_path / "source"  # built from a copy, so the build leaves nothing in the checkout
    shutil.copytree(REPO / "src", source / "src", ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(REPO / name, source / name)
    env = _clean_environment(tmp_path / "cache")
    _reuse_generated_spheres(tmp_path / "cache")
    wheels = tmp_path / "wheels"
    built = _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", str(source), "-w", str(wheels)],
                 tmp_path, env)
    assert built.returncode == 0, built.stderr[-2000:]
    (wheel,) = wheels.glob("kitchen_tamp-*.whl")

    venv = tmp_path / "venv"
    created = _run([sys.executable, "-m", "venv", str(venv)], tmp_path, env)
    assert created.returncode == 0, created.stderr
    pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "-q"]
    deps = _run([*pip, "-r", str(REPO / "requirements.txt")], tmp_path, env)
    if deps.returncode != 0:
        pytest.skip(f"cannot install the locked dependencies here (offline, no cache): {deps.stderr[-300:]}")
    installed = _run([*pip, "--no-index", "--no-deps", "--find-links", str(wheels), str(wheel)],
                     tmp_path, env)
    assert installed.returncode == 0, installed.stderr[-2000:]

    empty = tmp_path / "empty"
    empty.mkdir()
    python = str(venv / "bin" / "python")
    where = _run([python, "-c", "import kitchen_tamp; print(kitchen_tamp.__file__)"], empty, env)
    assert Path(where.stdout.strip()).is_relative_to(venv), where.stdout

    run = _run([str(venv / "bin" / "kitchen-tamp"), "rrt", "--no-video", "--out", "run"], empty, env, 900)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert "SOLVED and verified" in run.stdout
    assert (empty / "run" / "report.json").is_file()
    assert sorted(p.name for p in empty.iterdir()) == ["run"]  # nothing else written here

    planned = _run([str(venv / "bin" / "kitchen-tamp-plan"), "problem_hard.pddl"], empty, env)
    assert planned.returncode == 0, planned.stderr
    bfs = planned.stdout.split("BFS plan", 1)[1].split("--------------", 1)[0]
    steps = re.findall(r"^\d+\. \w+ .*$", bfs, re.MULTILINE)
    assert len(steps) == 7, planned.stdout
    assert sorted(p.name for p in empty.iterdir()) == ["run"]
