"""Joint-space box: the bounds planners sample from, and query validation."""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.collision_checker import JointConfiguration, JointConfigurations


class InvalidMotionQueryError(ValueError):
    """A start, goal or path has the wrong shape, is not finite, or leaves the joint bounds."""


@dataclass(frozen=True, eq=False)
class ConfigurationSpace:
    """Joint lower and upper bounds of a d-dimensional configuration space."""

    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]

    def __post_init__(self) -> None:
        lower = np.array(self.lower, dtype=np.float64)
        upper = np.array(self.upper, dtype=np.float64)
        if lower.ndim != 1 or lower.shape != upper.shape or lower.size == 0:
            raise ValueError(
                f"joint bounds must be two non-empty 1-D arrays of equal length, "
                f"got shapes {lower.shape} and {upper.shape}"
            )
        if not (np.all(np.isfinite(lower)) and np.all(np.isfinite(upper))):
            raise ValueError("joint bounds must be finite")
        if np.any(lower >= upper):
            joints = np.flatnonzero(lower >= upper).tolist()
            raise ValueError(f"lower bound must be below upper bound, not for joints {joints}")
        lower.flags.writeable = False
        upper.flags.writeable = False
        object.__setattr__(self, "lower", lower)
        object.__setattr__(self, "upper", upper)

    @functools.cached_property
    def diagonal(self) -> float:
        """The length of the box's diagonal: no two configurations are farther apart."""
        return float(np.linalg.norm(self.upper - self.lower))

    @property
    def dimension(self) -> int:
        """Number of joints d."""
        return int(self.lower.size)

    def sample_uniform(self, rng: np.random.Generator, count: int) -> JointConfigurations:
        """Draw `count` configurations uniformly from the box, shape (count, d): the values
        ``rng.uniform(lower, upper, size)`` draws (numpy computes ``lower + (upper - lower) * u`` from
        the same standard uniforms), in a third of its time."""
        return self.lower + (self.upper - self.lower) * rng.random((count, self.dimension))

    def contains(self, q: JointConfiguration) -> bool:
        """Whether `q` lies inside the bounds (inclusive)."""
        return bool(np.all(q >= self.lower) and np.all(q <= self.upper))

    def validated(self, q: npt.ArrayLike, name: str) -> JointConfiguration:
        """Return `q` as a float array of shape (d,), or raise `InvalidMotionQueryError`.

        `name` says which configuration this is ("start", "goal") in the message.
        """
        array = np.array(q, dtype=np.float64)
        if array.shape == self.lower.shape and bool(((array >= self.lower) & (array <= self.upper)).all()):
            return array  # within the bounds, so finite: the common case in one test
        if array.shape != (self.dimension,):
            raise InvalidMotionQueryError(f"{name} must have shape ({self.dimension},), got {array.shape}")
        if not np.all(np.isfinite(array)):
            raise InvalidMotionQueryError(f"{name} is not finite: {array.tolist()}")
        outside = np.flatnonzero((array < self.lower) | (array > self.upper))
        if outside.size:
            raise InvalidMotionQueryError(
                f"{name} is outside the joint bounds at joints {outside.tolist()}: "
                f"{array[outside].tolist()} not in "
                f"[{self.lower[outside].tolist()}, {self.upper[outside].tolist()}]"
            )
        return array
