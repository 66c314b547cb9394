"""Exceptions of the kitchen: bad problems for this kitchen and failed skills."""

from __future__ import annotations

from enum import StrEnum


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


class FailureKind(StrEnum):
    """Why a skill found no targets."""

    PRECONDITION = "precondition"
    """The scene contradicts the action (the hand is full, the drawer closed, the box elsewhere)."""
    NO_GRASP = "no_grasp"
    """The object fits no grasp of the hand."""
    TOO_LARGE = "too_large"
    """The object fits the region in no orientation, whatever else is there."""
    FULL = "full"
    """No sampled placement was free of the objects already there."""
    OBSTRUCTED = "obstructed"
    """Samples collided with other objects: removing them may make the action feasible."""
    UNREACHABLE = "unreachable"
    """No sample was reachable without collision, and no object is to blame."""


class SkillFailure(KitchenError):
    """No sampled target of a skill was reachable and collision-free; ``kind`` says why,
    ``objects`` which objects obstructed the samples (or fill the region, for ``full``), most
    often first, and ``region`` where the skill was to act."""

    def __init__(
        self,
        action: str,
        detail: str,
        kind: FailureKind = FailureKind.UNREACHABLE,
        objects: tuple[str, ...] = (),
        region: str | None = None,
    ) -> None:
        super().__init__(f"skill for {action} failed: {detail}")
        self.action = action
        self.detail = detail
        self.kind = kind
        self.objects = objects
        self.region = region


class UnknownActionError(KitchenError):
    """An action name (or arity) that no kitchen skill implements."""


class BindingFileError(KitchenError):
    """A domain's binding file that cannot bind it: one line with the file, the key and why."""

    def __init__(self, path: object, key: str, detail: str) -> None:
        super().__init__(f"{path}: {key}: {detail}" if key else f"{path}: {detail}")
        self.path = path
        self.key = key
