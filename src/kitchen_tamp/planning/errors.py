"""Exceptions of the planning package. Each message is one line a user can act on."""

from __future__ import annotations

from pathlib import Path


class PlanningInputError(Exception):
    """A PDDL file is missing, unreadable, malformed or inconsistent.

    The message starts with ``file:line:column:`` when the place is known, like
    a compiler's, so editors can jump to it.
    """

    def __init__(
        self, message: str, path: Path | str | None = None, line: int | None = None,
        column: int | None = None,
    ) -> None:
        self.path = Path(path) if path is not None else None
        self.line = line
        self.column = column
        self.reason = message
        place = ""
        if self.path is not None:
            place = str(self.path)
            if line is not None:
                place += f":{line}"
                if column is not None:
                    place += f":{column}"
            place += ": "
        super().__init__(place + message)


class SearchBudgetExhausted(Exception):
    """A search ran out of time or expansions before it could decide the task."""
