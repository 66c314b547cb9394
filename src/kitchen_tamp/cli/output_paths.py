"""Output locations checked before any planning, so that a run cannot end in a file it may not write.

An output folder is made ready by creating it and writing a probe file in it
(``prepare_output_folder``): permission bits say nothing for root, and a folder
under ``/proc`` or on a read-only mount passes every ``os.access`` test. An
output file (the planner's ``--plan-out``) is judged without creating anything.

Plain ``os.path`` work: ``pathlib`` and ``typing`` would cost every start of the activity
planner, which checks its ``--plan-out`` here.
"""

from __future__ import annotations

import os

PROBE_NAME = ".kitchen_tamp_write_probe"
"""The file ``prepare_output_folder`` writes and removes again."""


class OutputPathError(Exception):
    """An output folder or file the program could not write (exit 2)."""


def _nearest_existing(path: str | os.PathLike[str]) -> str:
    """``path`` itself if it exists, else its closest existing ancestor (where a write would create it)."""
    current = os.path.abspath(path)
    while not os.path.exists(current) and os.path.dirname(current) != current:
        current = os.path.dirname(current)
    return current


def _check_writable(folder: str | os.PathLike[str], given: str | os.PathLike[str], option: str) -> None:
    """Raise ``OutputPathError`` (naming ``option`` and the path the user ``given``) unless we may write
    in ``folder`` or create it."""
    existing = _nearest_existing(folder)
    if not os.path.isdir(existing):
        where = "" if existing == os.path.abspath(given) else f"{existing} "
        raise OutputPathError(f"{option} {os.fspath(given)}: {where}is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise OutputPathError(f"{option} {os.fspath(given)}: no permission to write in {existing}")


def prepare_output_folder(folder: str | os.PathLike[str], option: str) -> None:
    """Create ``folder`` (and its parents) and write and remove a probe file in it; raise
    ``OutputPathError`` naming ``option`` (the command-line option or default it came from)
    and the reason when either fails."""
    _check_writable(folder, folder, option)
    probe = os.path.join(folder, PROBE_NAME)
    try:
        os.makedirs(folder, exist_ok=True)
        with open(probe, "wb") as stream:
            stream.write(b"")
        os.unlink(probe)
    except OSError as error:
        raise OutputPathError(
            f"{option} {os.fspath(folder)}: cannot write there ({error.strerror or error})"
        ) from None


def check_output_file(path: str | os.PathLike[str], option: str) -> None:
    """Raise ``OutputPathError`` unless a file could be written (atomically, beside itself) at ``path``."""
    if os.path.isdir(path):
        raise OutputPathError(f"{option} {os.fspath(path)}: is a folder, not a file")
    _check_writable(os.path.dirname(os.path.abspath(path)), path, option)
