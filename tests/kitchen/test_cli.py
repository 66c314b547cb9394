from __future__ import annotations

from pathlib import Path

import pytest

from kitchen_tamp.kitchen.__main__ import main
from tests.kitchen.conftest import PROBLEMS, REPO


@pytest.mark.slow
def test_show_writes_pictures(tmp_path: Path) -> None:
    out = tmp_path / "scene.png"
    assert (
        main(["show", "--problem", str(REPO / "pddl" / "problem.pddl"), "--out", str(out), "--skills"]) == 0
    )
    assert out.read_bytes().startswith(b"\x89PNG")
    assert (tmp_path / "scene_skills.png").exists()


@pytest.mark.parametrize("problem", ["unknown_object.pddl", "mismatched_init.pddl", "missing.pddl"])
def test_bad_input_exits_with_2(tmp_path: Path, problem: str, capsys: pytest.CaptureFixture[str]) -> None:
    domain = REPO / "pddl" / "domain.pddl"
    code = main(
        [
            "show",
            "--problem",
            str(PROBLEMS / problem),
            "--domain",
            str(domain),
            "--out",
            str(tmp_path / "x.png"),
        ]
    )
    assert code == 2
    assert capsys.readouterr().err.startswith("error:")
