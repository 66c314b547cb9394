"""A PDDL file's path and text: reading it, and placing an error on the line it is about."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.reading.pddl_text import GRAMMAR_WORDS

_KEYWORD_OR_COMMENT = re.compile(r";[^\n]*|:[\w-]*[A-Z][\w-]*|(?<=\()\s*[\w-]*[A-Z][\w-]*")
"""A comment, or a ``:keyword`` or the word after an opening parenthesis with a capital letter in it."""
_UPPER_CASE_AFTER_COLON_OR_PARENTHESIS = re.compile(r":[\w-]*[A-Z]|\(\s*[\w-]*[A-Z]")
"""Where a keyword in upper case could be: most files have none, and are returned as they are."""


def lowercase_keywords(text: str) -> str:
    """``text`` with PDDL's keywords in lower case: ``(Define``, ``(:Init``, ``(AND`` as ``(define``, ...

    PDDL is case-insensitive and IPC files are written in every case (logistics' ``(Define``), but the
    ``pddl`` package's grammar knows its keywords in lower case only. Every ``:keyword`` and every
    grammar word right after an opening parenthesis is lowered; names, variables and comments are
    kept as written, and so is every position in the text (errors still point at the right column)."""
    def lower(match: re.Match[str]) -> str:
        token = match.group(0)
        if token[0] == ":" or (token[0] != ";" and token.strip().lower() in GRAMMAR_WORDS):
            return token.lower()
        return token

    if not _UPPER_CASE_AFTER_COLON_OR_PARENTHESIS.search(text):
        return text
    return _KEYWORD_OR_COMMENT.sub(lower, text)


def read_pddl(path: str | Path, what: str) -> str:
    """The text of a PDDL file, keywords in lower case (``lowercase_keywords``); a missing or unreadable
    file is an input error naming ``what``."""
    path = Path(path)
    if not path.exists():
        raise PlanningInputError(f"{what} file not found", path)
    if path.is_dir():
        raise PlanningInputError(f"{what} path is a directory, expected a PDDL file", path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise PlanningInputError(f"cannot read {what} file: {error}", path) from error
    return lowercase_keywords(text)


@dataclass(frozen=True, slots=True)
class PddlSource:
    """A read PDDL file with its text, kept for error messages."""

    path: str | Path
    text: str

    def locate(self, name: str, after: str | None = None) -> tuple[int | None, int | None]:
        """Line and column of the first whole-word ``name`` (after ``after`` if given)."""
        start = 0
        if after is not None:
            found = re.search(re.escape(after), self.text, re.IGNORECASE)
            start = found.start() if found else 0
        pattern = r"(?<![\w\-?])" + re.escape(name) + r"(?![\w\-])"
        match = re.compile(pattern, re.IGNORECASE).search(self.text, start)
        if match is None:
            return None, None
        line = self.text.count("\n", 0, match.start()) + 1
        column = match.start() - (self.text.rfind("\n", 0, match.start()) + 1) + 1
        return line, column

    def error(self, message: str, name: str | None = None, after: str | None = None) -> PlanningInputError:
        """An input error placed at ``name``'s first occurrence, if found."""
        line, column = self.locate(name, after) if name else (None, None)
        return PlanningInputError(message, self.path, line, column)
