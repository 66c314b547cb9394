"""Lighter copies of visual meshes for the GIF: the same surfaces with fewer triangles.

The tiny renderer's time goes into the triangles it rasterises, and the Panda's
visual meshes have about 100,000 of them, most far smaller than a pixel of
``replay.gif`` (at its camera distance a pixel spans about 8 mm). A copy made
by vertex clustering draws the same picture: vertices are snapped into cubes
of ``CLUSTER_SIZE``, each cube's vertices merge into their mean, and
triangles that collapse (two corners in one cube) or repeat are dropped.
Texture coordinates, normals, materials and the material library stay as
they are, so colours and shading are the original's. The copies are made once
per machine and kept in the user cache (``render_meshes/``), keyed by the
source file's contents and the cube size.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.user_cache import cache_directory

CLUSTER_SIZE = 0.010
"""Edge (m) of the cubes vertices are merged in: about a pixel of ``replay.gif``. The Panda's
101,735 visual triangles become 13,587 (19,758 at 8 mm, 9,532 at 12 mm); the robot's layer draws
in about 87% of the time 8 mm cubes took (12 mm: 78%), and at most 0.93% of a frame's pixels
differ by more than 40 levels from drawing the original meshes (8 mm: 0.86%, 12 mm: 1.02%;
`docs/pipeline.md`)."""
LOW_POLY_VERSION = "1"
"""Bump when what a copy holds changes (old copies are then not read)."""


def cluster_obj_text(text: str, cluster_size: float = CLUSTER_SIZE) -> str:
    """The OBJ ``text`` with its vertices merged per cube of ``cluster_size`` (m) and the
    triangles (faces) that collapse or repeat dropped; every other line kept."""
    lines = text.splitlines()
    vertices = np.array([[float(x) for x in line.split()[1:4]] for line in lines if line.startswith("v ")])
    if len(vertices) == 0:
        return text
    _, cluster, counts = np.unique(
        np.floor(vertices / cluster_size).astype(np.int64), axis=0, return_inverse=True, return_counts=True
    )
    cluster = cluster.ravel()
    sums = np.zeros((len(counts), 3))
    np.add.at(sums, cluster, vertices)
    merged = sums / counts[:, None]
    out = [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in merged]
    seen: set[tuple[int, ...]] = set()
    for line in lines:
        if line.startswith("v "):
            continue
        if line.startswith("f "):
            corners = [corner.split("/") for corner in line.split()[1:]]
            new = [int(cluster[int(corner[0]) - 1]) for corner in corners]
            key = tuple(sorted(new))
            if len(set(new)) < 3 or key in seen:
                continue
            seen.add(key)
            line = "f " + " ".join("/".join([str(n + 1), *c[1:]]) for n, c in zip(new, corners, strict=True))
        out.append(line)
    return "\n".join(out) + "\n"


def _supporting_files(obj: Path, text: str) -> list[Path]:
    """The material libraries the OBJ names and the texture maps they name, where they exist."""
    files = []
    for line in text.splitlines():
        if line.startswith("mtllib") and (obj.parent / line[6:].strip()).is_file():
            library = obj.parent / line[6:].strip()
            files.append(library)
            for entry in library.read_text(errors="replace").splitlines():
                if entry.strip().startswith("map_") and (obj.parent / entry.split()[-1]).is_file():
                    files.append(obj.parent / entry.split()[-1])
    return files


def low_poly_copy(source: Path, cluster_size: float = CLUSTER_SIZE) -> Path:
    """A clustered copy of the OBJ file ``source`` (with its materials and textures beside it) in
    the user cache; ``source`` itself when the cache cannot be written."""
    text = source.read_text(errors="replace")
    digest = hashlib.sha256(f"{LOW_POLY_VERSION} {cluster_size!r}".encode())
    digest.update(text.encode())
    folder = cache_directory() / "render_meshes" / digest.hexdigest()[:24]
    target = folder / source.name
    if target.is_file():
        return target
    try:
        folder.mkdir(parents=True, exist_ok=True)
        for supporting in _supporting_files(source, text):
            if not (folder / supporting.name).is_file():
                write_atomically(folder / supporting.name, supporting.read_bytes())
        return write_atomically(target, cluster_obj_text(text, cluster_size))
    except (OSError, RuntimeError):  # an unwritable cache costs the tiny renderer time, nothing else
        return source
