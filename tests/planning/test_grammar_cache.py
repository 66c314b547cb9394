"""The Lark grammar cache: built on a cold start, rebuilt when corrupt or stale, harmless when unwritable."""

from __future__ import annotations

import os
import pwd
from collections.abc import Iterator
from functools import cache
from pathlib import Path

import pytest
from pddl.core import Domain, Problem
from pddl.parser.domain import DomainParser, DomainTransformer
from pddl.parser.problem import ProblemParser, ProblemTransformer

from kitchen_tamp.planning.reading import grammar_cache
from kitchen_tamp.planning.reading.grammar_cache import StartSymbol, parse_with, pddl_parser
from kitchen_tamp.user_cache import cache_directory
from tests.planning.conftest import KITCHEN


@pytest.fixture
def builds(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[list[str]]:
    """An empty cache directory under ``tmp_path``; yields the start symbols built from the grammar."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    built: list[str] = []
    build = grammar_cache.build_parser

    def counting_build(start: StartSymbol, grammar: str) -> object:
        built.append(start)
        return build(start, grammar)

    monkeypatch.setattr(grammar_cache, "build_parser", counting_build)
    yield built


def cache_files() -> list[Path]:
    return sorted(cache_directory().glob("pddl-*.lark"))


@cache
def kitchen_texts() -> tuple[str, str]:
    return (KITCHEN / "domain.pddl").read_text(), (KITCHEN / "problem.pddl").read_text()


@cache
def parsed_by_the_pddl_package() -> tuple[Domain, Problem]:
    domain_text, problem_text = kitchen_texts()
    return DomainParser()(domain_text), ProblemParser()(problem_text)


def parses_the_kitchen() -> bool:
    """The cached parsers, with the transformers applied afterwards, give what the pddl package gives."""
    domain_text, problem_text = kitchen_texts()
    domain = parse_with(pddl_parser("domain"), DomainTransformer(), domain_text)
    problem = parse_with(pddl_parser("problem"), ProblemTransformer(), problem_text)
    return (domain, problem) == parsed_by_the_pddl_package()


def test_a_cold_start_builds_the_cache_and_later_starts_load_it(builds: list[str]) -> None:
    assert cache_directory().parent.name == "cache" and not cache_files()
    assert parses_the_kitchen()
    assert builds == ["domain", "problem"] and len(cache_files()) == 2
    assert parses_the_kitchen()
    assert builds == ["domain", "problem"]  # loaded, not built again


@pytest.mark.parametrize("damage", ["truncated", "garbage", "empty"])
def test_a_corrupt_cache_file_is_rebuilt(builds: list[str], damage: str) -> None:
    pddl_parser("domain")
    (path,) = cache_files()
    data = path.read_bytes()
    header_end = data.index(b"\n") + 1
    damaged = {"truncated": data[: header_end + (len(data) - header_end) // 2],
               "garbage": data[:header_end] + b"\x80\x05not a pickle at all",
               "empty": b""}[damage]
    path.write_bytes(damaged)
    assert parses_the_kitchen()
    assert builds == ["domain", "domain", "problem"]
    assert path.read_bytes() != damaged
    pddl_parser("domain")
    assert builds == ["domain", "domain", "problem"]  # the rewritten file loads


def test_a_stale_cache_is_not_used(builds: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    pddl_parser("domain")
    (path,) = cache_files()
    # The same file name with another key in its first line (e.g. written by another version).
    data = path.read_bytes()
    path.write_bytes(b"kitchen_tamp lark cache 0123\n" + data[data.index(b"\n") + 1:])
    pddl_parser("domain")
    assert builds == ["domain", "domain"]
    # A new lark or pddl version (here: a new cache format) means a new key, so a new file.
    monkeypatch.setattr(grammar_cache, "CACHE_FORMAT", grammar_cache.CACHE_FORMAT + 1)
    pddl_parser("domain")
    assert builds == ["domain", "domain", "domain"] and len(cache_files()) == 2


def test_an_unwritable_cache_directory_still_parses(builds: list[str]) -> None:
    cache_directory().parent.mkdir(parents=True)
    cache_directory().write_text("a file where the cache directory should be")
    assert parses_the_kitchen()
    assert parses_the_kitchen()
    assert builds == ["domain", "problem", "domain", "problem"]  # nothing cached, nothing failed


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories; "
                    "the file-in-the-way test covers an unwritable cache")
def test_a_read_only_cache_directory_still_parses(builds: list[str]) -> None:
    cache_directory().mkdir(parents=True)
    cache_directory().chmod(0o500)
    try:
        assert parses_the_kitchen()
        assert not cache_files()
    finally:
        cache_directory().chmod(0o700)


def test_without_a_home_directory_the_parser_is_built(
        builds: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.delenv("HOME", raising=False)

    def no_password_entry(uid: int) -> pwd.struct_passwd:
        raise KeyError(f"getpwuid(): uid not found: {uid}")

    monkeypatch.setattr(pwd, "getpwuid", no_password_entry)  # where os.path.expanduser looks next
    with pytest.raises(RuntimeError):
        Path.home()
    assert parses_the_kitchen()
    assert builds == ["domain", "problem"]


def test_xdg_cache_home_must_be_absolute(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/cache")
    assert cache_directory() == Path.home() / ".cache" / "kitchen_tamp"
    monkeypatch.delenv("XDG_CACHE_HOME")
    assert cache_directory() == Path.home() / ".cache" / "kitchen_tamp"
