"""The one interface between motion planning and whatever knows the geometry.

Planners see the world only through a `CollisionChecker`. The checker takes a
whole batch of joint configurations at once, so a vectorised checker (numpy
toy worlds today, perhaps a batched GPU checker later) pays its per-call
overhead once per batch, not once per configuration.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
import numpy.typing as npt

JointConfiguration = npt.NDArray[np.float64]
"""One joint configuration, shape (d,)."""

JointConfigurations = npt.NDArray[np.float64]
"""A batch of joint configurations, shape (n, d)."""

ValidityMask = npt.NDArray[np.bool_]
"""One flag per configuration of a batch, shape (n,): True when collision-free."""


class CollisionChecker(Protocol):
    """Decides which joint configurations (and straight segments) are collision-free."""

    def is_valid(self, qs: JointConfigurations) -> ValidityMask:
        """Return, for each row of `qs` (shape (n, d)), whether it is collision-free."""
        ...

    def segment_valid(self, q0: JointConfiguration, q1: JointConfiguration) -> bool:
        """Return whether the straight joint-space segment from `q0` to `q1` is collision-free.

        The checker chooses its own resolution. Our planners do not call this:
        they interpolate at their own resolution and call `is_valid` in
        batches, so the resolution is a hyper-parameter and every checked
        configuration is counted. It is here for consumers that verify paths
        with the checker's own notion of a segment (e.g. swept volumes).
        """
        ...
