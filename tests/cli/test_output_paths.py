"""Output locations are judged before any planning, without creating anything."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from kitchen_tamp.cli.output_paths import OutputPathError, check_output_file, check_output_folder


def test_a_folder_still_to_be_made_is_accepted_and_not_created(tmp_path: Path) -> None:
    check_output_folder(tmp_path / "a" / "b", "--out")
    check_output_file(tmp_path / "a" / "plan.txt", "--plan-out")
    assert list(tmp_path.iterdir()) == []


def test_a_file_in_the_way_is_named(tmp_path: Path) -> None:
    blocker = tmp_path / "x"
    blocker.write_text("")
    with pytest.raises(OutputPathError, match=f"--out {blocker}/y/z: {blocker} is a file, not a folder"):
        check_output_folder(blocker / "y" / "z", "--out")
    with pytest.raises(OutputPathError, match="is a folder, not a file"):
        check_output_file(tmp_path, "--plan-out")


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write in any folder: none is unwritable here")
def test_a_folder_without_write_permission_is_refused(tmp_path: Path) -> None:
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o555)
    with pytest.raises(OutputPathError, match=f"no permission to write in {locked}"):
        check_output_folder(locked / "run", "--out")
