"""Exceptions of the kitchen: bad problems for this kitchen and failed skills."""

from __future__ import annotations


class KitchenError(Exception):
    """Base class of the kitchen's errors."""


class UnknownObjectError(KitchenError):
    """A problem names an object (or gives it a type) that this kitchen does not have."""

    def __init__(self, name: str, detail: str) -> None:
        super().__init__(f"unknown kitchen object {name!r}: {detail}")
        self.name = name


class UnsupportedInitialStateError(KitchenError):
    """An initial state the kitchen cannot lay out (e.g. a box held at start, or not placed)."""


class InitialStateMismatchError(KitchenError):
    """The abstraction of the built scene differs from the problem's :init."""

    def __init__(self, missing: list[str], unexpected: list[str]) -> None:
        parts = []
        if missing:
            parts.append("in :init but not in the scene: " + ", ".join(missing))
        if unexpected:
            parts.append("in the scene but not in :init: " + ", ".join(unexpected))
        super().__init__("the kitchen scene does not match the problem's :init (" + "; ".join(parts) + ")")
        self.missing = missing
        self.unexpected = unexpected


class SkillFailure(KitchenError):
    """No sampled target of a skill was reachable and collision-free."""

    def __init__(self, action: str, detail: str) -> None:
        super().__init__(f"skill for {action} failed: {detail}")
        self.action = action


class UnknownActionError(KitchenError):
    """An action name (or arity) that no kitchen skill implements."""
