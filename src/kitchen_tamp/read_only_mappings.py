"""Read-only mappings that pickle: `read_only(items)` is a `types.MappingProxyType`, and every mapping
proxy pickles as the dict it shows and loads read-only again.

A mapping proxy does not pickle by itself, yet the judge's reading of a step, the replayed tracks
and the scene descriptions hold them and travel to the processes that execute physics and hold
Drake's models. Importing this module registers the one reducer (`copyreg`) for the process; a
loading process finds `read_only` by its name.
"""

from __future__ import annotations

import copyreg
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Any, TypeVar

Key = TypeVar("Key")
Value = TypeVar("Value")


def read_only(items: Mapping[Key, Value]) -> MappingProxyType[Key, Value]:
    """A read-only view of ``items`` (a dict: the view sees later changes to it)."""
    return MappingProxyType(items)


def _as_dict(
    mapping: MappingProxyType[Any, Any],
) -> tuple[Callable[..., MappingProxyType[Any, Any]], tuple[dict[Any, Any]]]:
    return read_only, (dict(mapping),)


copyreg.pickle(MappingProxyType, _as_dict)
