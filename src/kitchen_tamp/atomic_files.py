"""Writing output files atomically: a reader sees the old file or the new one, never half."""

from __future__ import annotations

import contextlib
import itertools
import os
from pathlib import Path

_TEMPORARY_NAMES = itertools.count()
"""Numbers the temporary files this process creates, so two writes never share one."""


def write_atomically(path: Path, data: str | bytes) -> Path:
    """Write ``data`` to a temporary file beside ``path``, then rename it over ``path``.

    Parent folders are created; the temporary file is removed if writing fails. The
    file gets the permissions of any new file (0o666 less the umask).
    """
    payload = data.encode("utf-8") if isinstance(data, str) else data
    path.parent.mkdir(parents=True, exist_ok=True)
    while True:  # a name left by a crashed process with the same number is skipped
        temporary = path.with_name(f".{path.name}.{os.getpid()}.{next(_TEMPORARY_NAMES)}.tmp")
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
        with contextlib.suppress(OSError):
            temporary.unlink()
        raise
    return path
