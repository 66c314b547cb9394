"""A PDDL file's path and text, kept so that a checking error can name the line it is about."""

from __future__ import annotations

from kitchen_tamp.planning.errors import PlanningInputError
from kitchen_tamp.planning.frozen_record import FrozenRecord

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from pathlib import Path


class PddlSource(FrozenRecord):
    """A read PDDL file with its text, kept for error messages."""

    __slots__ = ("path", "text")
    path: str | Path
    text: str

    def __init__(self, path: str | Path, text: str) -> None:
        self._set_fields(path=path, text=text)

    def locate(self, name: str, after: str | None = None) -> tuple[int | None, int | None]:
        """Line and column of the first whole-word ``name`` (after ``after`` if given)."""
        import re  # on use: only an error message needs it

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
