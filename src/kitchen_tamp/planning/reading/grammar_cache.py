"""The ``pddl`` package's Lark parsers, built once per machine and then loaded from the user's cache.

Building a Lark LALR parser analyses the grammar afresh (about 0.15 s per
start symbol for the PDDL grammar), which used to be most of the wall time of
a small ``activity_planning.py`` run. The built parser is saved with Lark's
own ``Lark.save`` in ``$XDG_CACHE_HOME/kitchen_tamp`` (``~/.cache/kitchen_tamp``
when that is unset) and loaded with ``Lark.load`` by later processes, in about
7 ms.

A cache file's name and its first line carry a key: the cache format, the
``pddl`` and Lark versions, the Python version and the SHA-256 of the grammar
text with its start symbol. A file whose first line does not match (stale) or
that Lark cannot load (truncated, corrupt) is a miss: the parser is built and
the file written again. Files are written atomically (a temporary file renamed
over the old one), so concurrent processes see a whole file or none; a cache
directory that cannot be written (read-only, a file in the way) only means
building the parser every run, never an error.

The cached parsers produce trees; the ``pddl`` package's transformers turn
them into its objects afterwards (``parse_with``), which costs the same as
transforming while parsing.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import sys
from pathlib import Path
from typing import Any, Literal, TypeVar

import lark
from lark import Lark, Transformer
from lark.exceptions import VisitError
from pddl.__version__ import __version__ as pddl_version
from pddl.parser import GRAMMAR_FILE, PARSERS_DIRECTORY

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.user_cache import cache_directory

T = TypeVar("T")

CACHE_FORMAT = 1
"""Bumped when the layout of the cache files changes."""

StartSymbol = Literal["domain", "problem"]


def cache_key(start: StartSymbol, grammar: str) -> str:
    """What a cached parser depends on, as a short hex digest."""
    identity = "\0".join((str(CACHE_FORMAT), pddl_version, lark.__version__,
                          f"{sys.version_info[0]}.{sys.version_info[1]}", start, grammar))
    return hashlib.sha256(identity.encode("utf-8")).hexdigest()[:32]


def cache_path(start: StartSymbol, key: str) -> Path:
    return cache_directory() / f"pddl-{start}-{key}.lark"


def build_parser(start: StartSymbol, grammar: str) -> Lark:
    """The LALR parser the ``pddl`` package builds for ``start``, without its transformer."""
    return Lark(grammar, parser="lalr", import_paths=[PARSERS_DIRECTORY], start=start)


def pddl_parser(start: StartSymbol) -> Lark:
    """The parser for ``start``: loaded from the cache if it holds a current one, else built and cached."""
    grammar = GRAMMAR_FILE.read_text(encoding="utf-8")
    key = cache_key(start, grammar)
    try:
        path: Path | None = cache_path(start, key)
    except RuntimeError:  # no home directory to be found: no cache, not an error
        path = None
    parser = _load(path, key) if path is not None else None
    if parser is None:
        parser = build_parser(start, grammar)
        if path is not None:
            _store(parser, path, key)
    return parser


def parse_with(parser: Lark, transformer: Transformer[Any, T], text: str) -> T:
    """Parse ``text`` and transform the tree; errors raised by the transformer come out unwrapped."""
    tree = parser.parse(text)
    try:
        return transformer.transform(tree)
    except VisitError as error:
        raise error.orig_exc from None


def _header(key: str) -> bytes:
    return f"kitchen_tamp lark cache {key}\n".encode("ascii")


def _load(path: Path, key: str) -> Lark | None:
    try:
        with path.open("rb") as stream:
            if stream.readline() != _header(key):
                return None
            return Lark.load(stream)
    except Exception:  # missing, unreadable, truncated or corrupt: a cache miss, the parser is rebuilt
        return None


def _store(parser: Lark, path: Path, key: str) -> None:
    buffer = io.BytesIO()
    buffer.write(_header(key))
    parser.save(buffer)
    with contextlib.suppress(OSError):  # an unwritable cache directory costs time next run, nothing else
        write_atomically(path, buffer.getvalue())
