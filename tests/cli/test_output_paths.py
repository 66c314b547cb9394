"""Output locations are judged before any planning: a folder by creating it and writing a probe
in it, a file without creating anything."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from kitchen_tamp.cli.output_paths import (
    PROBE_NAME,
    OutputPathError,
    check_output_file,
    prepare_output_folder,
)


def test_a_folder_still_to_be_made_is_made_and_probed(tmp_path: Path) -> None:
    prepare_output_folder(tmp_path / "a" / "b", "--out")
    assert (tmp_path / "a" / "b").is_dir() and not (tmp_path / "a" / "b" / PROBE_NAME).exists()
    check_output_file(tmp_path / "c" / "plan.txt", "--plan-out")
    assert not (tmp_path / "c").exists()


def test_a_folder_no_one_can_write_is_refused_even_for_root() -> None:
    """Under /proc no file can be made, whatever the permission bits say to root."""
    with pytest.raises(OutputPathError, match="--out /proc/no/such/dir: cannot write there"):
        prepare_output_folder(Path("/proc/no/such/dir"), "--out")


def test_a_file_in_the_way_is_named(tmp_path: Path) -> None:
    blocker = tmp_path / "x"
    blocker.write_text("")
    with pytest.raises(OutputPathError, match=f"--out {blocker}/y/z: {blocker} is a file, not a folder"):
        prepare_output_folder(blocker / "y" / "z", "--out")
    with pytest.raises(OutputPathError, match="is a folder, not a file"):
        check_output_file(tmp_path, "--plan-out")


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write in any folder: none is unwritable here")
def test_a_folder_without_write_permission_is_refused(tmp_path: Path) -> None:
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o555)
    with pytest.raises(OutputPathError, match=f"no permission to write in {locked}"):
        prepare_output_folder(locked / "run", "--out")
