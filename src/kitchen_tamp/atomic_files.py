"""Writing output files atomically: a reader sees the old file or the new one, never half."""

from __future__ import annotations

import itertools
import os

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: the planner's start-up writes its task cache with this
if TYPE_CHECKING:
    from pathlib import Path

_TEMPORARY_NAMES = itertools.count()
"""Numbers the temporary files this process creates, so two writes never share one."""


def write_atomically(path: Path, data: str | bytes) -> Path:
    """Write ``data`` to a temporary file beside ``path``, then rename it over ``path``.

    Parent folders are created; the temporary file is removed if writing fails. The
    file gets the permissions of any new file (0o666 less the umask).
    """
    write_file_atomically(os.fspath(path), data.encode("utf-8") if isinstance(data, str) else data)
    return path


def write_file_atomically(path: str, payload: bytes) -> None:
    """``write_atomically`` for a path given as a string, without importing ``pathlib``."""
    folder = os.path.dirname(path) or "."
    os.makedirs(folder, exist_ok=True)
    while True:  # a name left by a crashed process with the same number is skipped
        name = f".{os.path.basename(path)}.{os.getpid()}.{next(_TEMPORARY_NAMES)}.tmp"
        temporary = os.path.join(folder, name)
        try:
            handle = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
            break
        except FileExistsError:
            continue
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(payload)
        os.replace(temporary, path)
    except BaseException:
        try:  # noqa: SIM105 (contextlib is one more import on the planner's start-up)
            os.unlink(temporary)
        except OSError:
            pass
        raise
