"""Exceptions raised by the world package."""

from __future__ import annotations


class WorldError(Exception):
    """Base class of every error the simulated world raises."""


class UnknownNameError(WorldError, LookupError):
    """A body, link or joint name that the scene or the body does not have."""


class SceneClosedError(WorldError):
    """The scene's physics client was already disconnected."""
