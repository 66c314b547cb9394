"""Output locations checked before any planning, so that a run cannot end in a file it may not write."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path


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


def check_output_folder(folder: Path, option: str) -> None:
    """Raise ``OutputPathError`` unless ``folder`` is, or could be created as, a folder we may write in.

    Nothing is created: a missing folder is judged by its closest existing ancestor.
    ``option`` names the command-line option (or default) the folder came from.
    """
    _check_writable(folder, folder, option)


def check_output_file(path: Path, option: str) -> None:
    """Raise ``OutputPathError`` unless a file could be written (atomically, beside itself) at ``path``."""
    if path.is_dir():
        raise OutputPathError(f"{option} {path}: is a folder, not a file")
    _check_writable(path.parent, path, option)
