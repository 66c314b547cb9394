"""The sphere kernels compiled ahead of time (`kernels.loading`, built by ``make install``): the JIT
kernels' answers to the bit, a kitchen run's checks without importing numba, and a module name
that changes with the kernels' sources and the processor."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from kitchen_tamp import ahead_of_time_modules
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.clearance import SphereClearance
from kitchen_tamp.motion.geometry.spheres.kernels import loading
from tests.motion import test_sphere_pair_tables

checkers = test_sphere_pair_tables.checkers
"""The fixture: the free hand, and the hand holding spam as the pick skill grasped it."""

REPO = Path(__file__).resolve().parents[2]
NOT_BUILT = (
    "no module compiled ahead of time for these kernel sources on this processor: "
    "`make install` (python -m kitchen_tamp.cli.prepare) builds it"
)


@pytest.fixture(scope="module")
def module() -> ModuleType:
    built = loading.AHEAD_OF_TIME.load()
    if built is None:
        pytest.skip(NOT_BUILT)
    return built


def _configurations(checker: SphereCollisionChecker, seed: int) -> np.ndarray:
    """Uniform configurations, and as many near the middle of the limits (where more pairs are close)."""
    rng = np.random.default_rng(seed)
    uniform = rng.uniform(checker.lower, checker.upper, size=(3000, 7))
    middle = (checker.lower + checker.upper) / 2 + rng.normal(0.0, 0.4, size=(3000, 7))
    return np.ascontiguousarray(np.vstack([uniform, middle]))


def test_ahead_of_time_validity_is_the_jits(
    checkers: list[SphereCollisionChecker], module: ModuleType
) -> None:
    ahead, jit = loading.ahead_of_time_kernels(module), loading.jit_kernels()
    for seed, checker in enumerate(checkers):
        qs = _configurations(checker, seed)
        arguments = checker.kernel_arguments
        for stop_at_invalid in (False, True):
            got = ahead.valid(qs, ahead.pack(arguments), checker.margin, stop_at_invalid)
            want = jit.valid(qs, jit.pack(arguments), checker.margin, stop_at_invalid)
            np.testing.assert_array_equal(got, want)
            if not stop_at_invalid:
                assert 0.05 < np.mean(want) < 0.95  # both verdicts are asked for


def test_ahead_of_time_clearance_is_the_jits_to_the_bit(
    checkers: list[SphereCollisionChecker], module: ModuleType
) -> None:
    ahead, jit = loading.ahead_of_time_kernels(module), loading.jit_kernels()
    for seed, checker in enumerate(checkers):
        clearance = SphereClearance(checker.model, 0.005)
        qs = _configurations(checker, 10 + seed)
        arguments = (qs, clearance._arguments, clearance.floors, clearance.width)
        got, want = ahead.clearance_penalties(*arguments), jit.clearance_penalties(*arguments)
        assert np.count_nonzero(want[0]) > 100  # pairs within the influence width
        for got_array, want_array in zip(got, want, strict=True):
            assert np.array_equal(got_array, want_array)  # bit for bit: the optimiser's iterates follow


def test_a_kitchen_check_served_ahead_of_time_imports_no_numba(module: ModuleType) -> None:
    program = """
import sys
import numpy as np
from kitchen_tamp.kitchen.scene.layout import load_kitchen_problem
from kitchen_tamp.motion.geometry.spheres import SphereClearance, SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.loading import sphere_kernels
from kitchen_tamp.world import describe_collision_checker
_, built = load_kitchen_problem(sys.argv[1])
with built as kitchen:
    checker = SphereCollisionChecker(describe_collision_checker(kitchen.collision_checker()))
    home = np.atleast_2d(kitchen.arm_configuration())
assert checker.is_valid(home).all()
SphereClearance(checker.model, 0.005, ends=home)(home)
assert sphere_kernels().ahead_of_time
print("numba" in sys.modules)
"""
    done = subprocess.run([sys.executable, "-c", program, str(REPO / "pddl" / "problem.pddl")],
                          capture_output=True, text=True, cwd=REPO, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split()[-1] == "False"


def test_module_name_follows_the_sources_and_the_processor(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    sources = {path.name for path in loading.AHEAD_OF_TIME.sources}
    assert {"validity.py", "clearance.py", "primitives.py", "tree_walks.py"} <= sources
    name = loading.AHEAD_OF_TIME.name()
    assert name.startswith(loading.AHEAD_OF_TIME.prefix)
    first = loading.AHEAD_OF_TIME.sources[0]
    edited = tmp_path / first.name  # the same file with one more line
    edited.write_text(first.read_text() + "\n")
    with_edit = replace(loading.AHEAD_OF_TIME, sources=(edited, *loading.AHEAD_OF_TIME.sources[1:]))
    assert with_edit.name() != name
    monkeypatch.setattr(ahead_of_time_modules, "processor_signature", lambda: "another processor")
    assert loading.AHEAD_OF_TIME.name() != name
