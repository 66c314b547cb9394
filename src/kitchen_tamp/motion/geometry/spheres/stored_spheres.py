"""Where generated sphere sets and pair tables are kept: shipped in the package, else the user cache.

Covering the Panda's meshes with spheres and proving its pair tables take a
couple of minutes of one core, for results that are the same on every machine
(the meshes come with ``pybullet_data``). So the package ships them, for the
robot and for the boxes of the default kitchen and the galley:
``shipped/coverings.json`` (sphere sets by key) and ``shipped/pair_tables.npz``
(proved cells by key), made by ``python -m kitchen_tamp.cli.shipped_spheres``,
whose test regenerates them and compares. A key says what was covered or proved
(the shape, the tolerance, the method's version; see ``scene`` and
``pair_tables``), so a shipped entry is found only for exactly that; anything
else (another kitchen's boxes, a changed mesh) is generated on first use and
kept in the user cache (``spheres/`` in ``kitchen_tamp.user_cache``).
"""

from __future__ import annotations

import contextlib
import functools
import io
import json
from collections.abc import Iterator
from importlib.resources import files
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.motion.geometry.spheres.covering import SphereSet
from kitchen_tamp.user_cache import cache_directory

SHIPPED_COVERINGS = "coverings.json"
SHIPPED_PAIR_TABLES = "pair_tables.npz"
_reading_shipped = [True]
"""Whether lookups read the shipped files (off while they are regenerated)."""


def sphere_cache_directory() -> Path:
    """Where generated sphere sets are kept between runs: ``spheres/`` in kitchen_tamp's
    cache directory (``kitchen_tamp.user_cache``)."""
    return cache_directory() / "spheres"


def shipped_directory() -> Path:
    """The folder of the shipped files, inside the package."""
    return Path(str(files("kitchen_tamp.motion.geometry.spheres") / "shipped"))


@contextlib.contextmanager
def ignoring_shipped() -> Iterator[None]:
    """Lookups within see only the user cache (to regenerate what is shipped)."""
    _reading_shipped[0] = False
    try:
        yield
    finally:
        _reading_shipped[0] = True


@functools.cache
def _shipped_coverings() -> dict[str, Any]:
    try:
        data: dict[str, Any] = json.loads((shipped_directory() / SHIPPED_COVERINGS).read_text())
        return data
    except (OSError, ValueError):
        return {}


@functools.cache
def _shipped_tables() -> Any:
    try:
        return np.load(shipped_directory() / SHIPPED_PAIR_TABLES)
    except (OSError, ValueError):
        return {}


def _sphere_set(stored: dict[str, Any]) -> SphereSet:
    return SphereSet(np.array(stored["centers"], dtype=float).reshape(-1, 3),
                     np.array(stored["radii"], dtype=float))


def load_covering(key: str) -> SphereSet | None:
    """The sphere set stored under ``key``: shipped, else in the user cache, else None."""
    if _reading_shipped[0] and key in _shipped_coverings():
        return _sphere_set(_shipped_coverings()[key])
    try:
        return _sphere_set(json.loads((sphere_cache_directory() / f"{key}.json").read_text()))
    except (OSError, ValueError, KeyError, RuntimeError):
        return None


def save_covering(key: str, spheres: SphereSet) -> None:
    """Keeps ``spheres`` in the user cache under ``key`` (an unwritable cache only costs time)."""
    text = json.dumps({"centers": spheres.centers.tolist(), "radii": spheres.radii.tolist()})
    with contextlib.suppress(OSError, RuntimeError):
        write_atomically(sphere_cache_directory() / f"{key}.json", text)


def load_pair_cells(key: str) -> npt.NDArray[np.int8] | None:
    """The proved cells of a pair table stored under ``key``: shipped, else in the user cache."""
    if _reading_shipped[0] and key in _shipped_tables():
        return np.asarray(_shipped_tables()[key], dtype=np.int8)
    try:
        return np.asarray(np.load(sphere_cache_directory() / f"pairs-{key}.npy"), dtype=np.int8)
    except (OSError, ValueError, RuntimeError):
        return None


def save_pair_cells(key: str, cells: npt.NDArray[np.int8]) -> None:
    """Keeps a table's cells in the user cache under ``key``."""
    buffer = io.BytesIO()
    np.save(buffer, cells)
    with contextlib.suppress(OSError, RuntimeError):
        write_atomically(sphere_cache_directory() / f"pairs-{key}.npy", buffer.getvalue())


def read_store(folder: Path) -> tuple[dict[str, SphereSet], dict[str, npt.NDArray[np.int8]]]:
    """Every sphere set and pair table in a cache folder (``spheres/`` as the lookups write it)."""
    coverings = {path.stem: _sphere_set(json.loads(path.read_text()))
                 for path in sorted(folder.glob("*.json"))}
    tables = {path.stem.removeprefix("pairs-"): np.load(path) for path in sorted(folder.glob("pairs-*.npy"))}
    return coverings, tables


def read_shipped() -> tuple[dict[str, SphereSet], dict[str, npt.NDArray[np.int8]]]:
    """Every shipped sphere set and pair table."""
    tables = _shipped_tables()
    return ({key: _sphere_set(value) for key, value in _shipped_coverings().items()},
            {key: np.asarray(tables[key]) for key in tables})


def write_shipped(
    coverings: dict[str, SphereSet], tables: dict[str, npt.NDArray[np.int8]], folder: Path
) -> None:
    """Writes the shipped files into ``folder`` (keys sorted, so the same data give the same files)."""
    data = {key: {"centers": coverings[key].centers.tolist(), "radii": coverings[key].radii.tolist()}
            for key in sorted(coverings)}
    write_atomically(folder / SHIPPED_COVERINGS, json.dumps(data, indent=0) + "\n")
    buffer = io.BytesIO()
    arrays: dict[str, Any] = {key: tables[key] for key in sorted(tables)}
    np.savez_compressed(buffer, **arrays)
    write_atomically(folder / SHIPPED_PAIR_TABLES, buffer.getvalue())
    _shipped_coverings.cache_clear()
    _shipped_tables.cache_clear()
