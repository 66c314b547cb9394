"""Output locations checked before any planning, so that a run cannot end in a file it may not write.

An output folder is made ready by creating it and writing a probe file in it
(``prepare_output_folder``): permission bits say nothing for root, and a folder
under ``/proc`` or on a read-only mount passes every ``os.access`` test. An
output file (the planner's ``--plan-out``) is judged without creating anything.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path

PROBE_NAME = ".kitchen_tamp_write_probe"
"""The file ``prepare_output_folder`` writes and removes again."""


class OutputPathError(Exception):
    """An output folder or file the program could not write (exit 2)."""


def _nearest_existing(path: Path) -> Path:
    """``path`` itself if it exists, else its closest existing ancestor (where a write would create it)."""
    current = path.absolute()
    while not current.exists() and current != current.parent:
        current = current.parent
    return current


def _check_writable(folder: Path, given: Path, option: str) -> None:
    """Raise ``OutputPathError`` (naming ``option`` and the path the user ``given``) unless we may write
    in ``folder`` or create it."""
    existing = _nearest_existing(folder)
    if not existing.is_dir():
        where = "" if existing == given.absolute() else f"{existing} "
        raise OutputPathError(f"{option} {given}: {where}is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise OutputPathError(f"{option} {given}: no permission to write in {existing}")


def prepare_output_folder(folder: Path, option: str) -> None:
    """Create ``folder`` (and its parents) and write and remove a probe file in it; raise
    ``OutputPathError`` naming ``option`` (the command-line option or default it came from)
    and the reason when either fails."""
    _check_writable(folder, folder, option)
    probe = folder / PROBE_NAME
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as error:
        raise OutputPathError(f"{option} {folder}: cannot write there ({error.strerror or error})") from None


def check_output_file(path: Path, option: str) -> None:
    """Raise ``OutputPathError`` unless a file could be written (atomically, beside itself) at ``path``."""
    if path.is_dir():
        raise OutputPathError(f"{option} {path}: is a folder, not a file")
    _check_writable(path.parent, path, option)
