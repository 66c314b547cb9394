"""Building the greedy search in C: a library named after its source, written whole or not at all."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from kitchen_tamp.planning.search import native_greedy


@pytest.fixture
def copied_source(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The search's source copied into a folder of its own, where the library is built."""
    source = tmp_path / "greedy_search.c"
    shutil.copy(native_greedy.SOURCE, source)
    monkeypatch.setattr(native_greedy, "SOURCE", source)
    return source


def test_a_failing_compiler_leaves_no_library_and_no_partial_file(copied_source: Path,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    if shutil.which("false") is None:
        pytest.skip("no `false` command to stand for a failing compiler")
    monkeypatch.setenv("CC", "false")
    with pytest.raises(subprocess.CalledProcessError):
        native_greedy.compile_library()
    built = copied_source.parent / "__pycache__"
    assert not built.exists() or not any(built.iterdir())
    assert native_greedy.load_library() is None


def test_a_missing_compiler_raises_os_error(copied_source: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("CC", "no-such-compiler-here")
    with pytest.raises(OSError):
        native_greedy.compile_library()


def test_an_edited_source_is_not_served_by_the_old_library(copied_source: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    if shutil.which("cc") is None and shutil.which("gcc") is None:
        pytest.skip("no C compiler here")
    monkeypatch.delenv("CC", raising=False)
    first = native_greedy.compile_library()
    assert native_greedy.load_library() is not None
    copied_source.write_text(copied_source.read_text() + "\n/* edited */\n")
    assert native_greedy.library_path() != first
    assert native_greedy.load_library() is None  # until the next build
    second = native_greedy.compile_library()
    assert second.exists() and not first.exists()  # the old source's library is removed
