"""The files a run is judged against -- its problem, domain and kitchen scene -- with the
SHA-256 digest of each, and whether each is, byte for byte, the file the run planned with.

A run records each file's path and digest (in ``trajectory.json`` and
``report.json``). ``replay`` judges against the recorded paths unless
``--problem``, ``--domain`` or ``--scene`` name others, and says for each file it
judged against whether its digest is the one the run recorded: a file edited
since (a weaker goal, a thinner robot mount) shows as different, and a
trajectory file that points at other files than the ones the user trusts is
judged against the trusted ones when the user names them.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Final

INPUT_ROLES: Final = ("problem", "domain", "scene")
"""The files of a run, in the order they are reported."""


def file_digest(path: Path) -> str | None:
    """The SHA-256 of the file's bytes in hex, or None if it cannot be read."""
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except OSError:
        return None


@dataclass(frozen=True)
class InputFile:
    """One file judged against: its path, its digest now, and the digest the run recorded
    (None when the run recorded none)."""

    role: str
    path: Path
    sha256: str | None
    recorded_sha256: str | None = None

    @property
    def matches_run(self) -> bool | None:
        """Whether the file is the one the run planned with (None: the run recorded no digest)."""
        if self.recorded_sha256 is None:
            return None
        return self.sha256 == self.recorded_sha256

    def data(self) -> dict[str, object]:
        return {"path": str(self.path), "sha256": self.sha256, "matches_run": self.matches_run}

    def words(self) -> str:
        """E.g. ``problem.pddl (as planned)``."""
        verdict = {True: "as planned", False: "DIFFERENT from the run's", None: "no digest recorded"}
        return f"{self.path.name} ({verdict[self.matches_run]})"


@dataclass(frozen=True)
class RunInputs:
    """The problem, domain and scene files of a run."""

    files: tuple[InputFile, ...]

    @classmethod
    def of(cls, paths: Mapping[str, Path], recorded: Mapping[str, str] | None = None) -> RunInputs:
        """The files at ``paths`` (role -> path) now, compared with the ``recorded`` digests
        (role -> SHA-256; None when planning: the files are the run's by definition)."""
        files = []
        for role in INPUT_ROLES:
            if role in paths:
                digest = file_digest(paths[role])
                expected = digest if recorded is None else recorded.get(role)
                files.append(InputFile(role, paths[role], digest, expected))
        return cls(tuple(files))

    def digests(self) -> dict[str, str]:
        """Role -> SHA-256 of each readable file (what a run records)."""
        return {f.role: f.sha256 for f in self.files if f.sha256 is not None}

    def data(self) -> dict[str, object]:
        """The ``inputs`` section of a report."""
        return {f.role: f.data() for f in self.files}

    def words(self) -> str:
        """E.g. ``judged against problem.pddl (as planned), domain.pddl (as planned), ...``."""
        return "judged against " + ", ".join(f"{f.role} {f.words()}" for f in self.files)
