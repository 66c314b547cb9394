"""OBJ meshes as Meshcat's browser code can load them: without texture coordinates.

Some of the Panda's visual meshes give texture coordinates to some of their parts
and not to others; Meshcat's JavaScript merges the parts of an OBJ and fails on
such a mix (``mergeGeometries() failed``, the link not drawn). The texture only
tints the materials, whose colours are in the MTL files, so the copy sent to the
browser drops texture coordinates and maps, comments, and material libraries
that do not exist. Geometry, normals and materials are the file's own. The copies
are kept in the user cache (``untextured_meshes/``).
"""

from __future__ import annotations

import contextlib
import hashlib
import re
from functools import lru_cache
from pathlib import Path

from pydrake.common import MemoryFile
from pydrake.geometry import InMemoryMesh

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.user_cache import cache_directory

UNTEXTURED_VERSION = "1"
"""Bump when what `untextured_obj_text` leaves changes (kept copies are then not read)."""

_DROPPED_OBJ_LINES = re.compile(r"^(?:vt\s|#).*\n?", re.MULTILINE)
_TEXTURE_INDEX = re.compile(r"/\d*/")
"""``v/vt/vn`` -> ``v//vn``."""
_TEXTURE_ONLY_INDEX = re.compile(r"(?<=\d)/\d+(?=\s|$)", re.MULTILINE)
"""``v/vt`` -> ``v`` (run after ``_TEXTURE_INDEX``, so ``v//vn`` is left alone)."""
_MATERIAL_LIBRARY = re.compile(r"^mtllib[ \t]+(.*?)\s*$", re.MULTILINE)
_DROPPED_MTL_LINES = re.compile(r"^\s*(?:map_|#).*\n?", re.MULTILINE)


def untextured_obj_text(text: str, libraries: frozenset[str]) -> str:
    """The OBJ ``text`` without texture coordinates, comments and ``mtllib`` lines other than
    ``libraries``."""
    text = _TEXTURE_ONLY_INDEX.sub("", _TEXTURE_INDEX.sub("//", _DROPPED_OBJ_LINES.sub("", text)))
    if "mtllib" not in text:
        return text
    return "\n".join(
        line for line in text.splitlines() if not line.startswith("mtllib") or line[6:].strip() in libraries
    ) + "\n"


def untextured_mtl_text(text: str) -> str:
    """The MTL ``text`` without texture maps and comments: materials keep their colours."""
    return _DROPPED_MTL_LINES.sub("", text)


def _kept_copy(obj: Path, libraries: frozenset[str]) -> str:
    """The untextured text of ``obj``, from the user cache when it was made before (the regular
    expressions take about a second for the Panda's meshes), keyed by the file's path, size and
    modification time."""
    status = obj.stat()
    key = hashlib.sha256(
        f"{UNTEXTURED_VERSION}|{obj.resolve()}|{status.st_size}|{status.st_mtime_ns}|{sorted(libraries)}".encode()
    ).hexdigest()[:24]
    try:
        kept: Path | None = cache_directory() / "untextured_meshes" / f"{key}.obj"
    except RuntimeError:  # no home directory: nothing is kept
        kept = None
    if kept is not None and kept.is_file():
        return kept.read_text()
    text = untextured_obj_text(obj.read_text(errors="replace"), libraries)
    if kept is not None:
        with contextlib.suppress(OSError):  # an unwritable cache only costs time
            write_atomically(kept, text)
    return text


def material_library_names(text: str) -> list[str]:
    """What the ``mtllib`` lines of the OBJ ``text`` name, in order (the lines found with
    ``str.find``: the regular expression over the whole of the Panda's 9 MB of meshes took 80 ms
    of every ``replay.html``)."""
    names = []
    at = text.find("mtllib")
    while at >= 0:
        end = text.find("\n", at)
        if at == 0 or text[at - 1] == "\n":
            names += _MATERIAL_LIBRARY.findall(text[at : len(text) if end < 0 else end])
        at = text.find("mtllib", at + len("mtllib"))
    return names


@lru_cache(maxsize=32)
def untextured_obj_mesh(path: str) -> InMemoryMesh:
    """The OBJ file at ``path`` and the material libraries it names, untextured, in memory."""
    obj = Path(path)
    libraries = {}
    for name in material_library_names(obj.read_text(errors="replace")):
        if (obj.parent / name).is_file():
            libraries[name] = MemoryFile(
                untextured_mtl_text((obj.parent / name).read_text(errors="replace")), ".mtl", name
            )
    return InMemoryMesh(
        mesh_file=MemoryFile(_kept_copy(obj, frozenset(libraries)), ".obj", obj.name),
        supporting_files=libraries,
    )
