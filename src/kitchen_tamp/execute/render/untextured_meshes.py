"""OBJ meshes as Meshcat's browser code can load them: without texture coordinates.

Some of the Panda's visual meshes give texture coordinates to some of their parts
and not to others; Meshcat's JavaScript merges the parts of an OBJ and fails on
such a mix (``mergeGeometries() failed``, the link not drawn). The texture only
tints the materials, whose colours are in the MTL files, so the copy sent to the
browser drops texture coordinates and maps, comments, and material libraries
that do not exist. Geometry, normals and materials are the file's own.
"""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

from pydrake.common import MemoryFile
from pydrake.geometry import InMemoryMesh

_DROPPED_OBJ_LINES = re.compile(r"^(?:vt\s|#).*\n?", re.MULTILINE)
_TEXTURE_INDEX = re.compile(r"/\d*/")
"""``v/vt/vn`` -> ``v//vn``."""
_TEXTURE_ONLY_INDEX = re.compile(r"(?<=\d)/\d+(?=\s|$)", re.MULTILINE)
"""``v/vt`` -> ``v`` (run after ``_TEXTURE_INDEX``, so ``v//vn`` is left alone)."""
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


@lru_cache(maxsize=32)
def untextured_obj_mesh(path: str) -> InMemoryMesh:
    """The OBJ file at ``path`` and the material libraries it names, untextured, in memory."""
    obj = Path(path)
    text = obj.read_text(errors="replace")
    libraries = {}
    for line in text.splitlines():
        if line.startswith("mtllib"):
            name = line[6:].strip()
            if (obj.parent / name).is_file():
                libraries[name] = MemoryFile(
                    untextured_mtl_text((obj.parent / name).read_text(errors="replace")), ".mtl", name
                )
    return InMemoryMesh(
        mesh_file=MemoryFile(untextured_obj_text(text, frozenset(libraries)), ".obj", obj.name),
        supporting_files=libraries,
    )
