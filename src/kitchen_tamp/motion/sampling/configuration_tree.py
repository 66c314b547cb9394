"""A tree of joint configurations with vectorised nearest-neighbour search.

Nodes live in a preallocated (capacity, d) array that doubles when full, so
finding the nearest node is one matrix-vector product over the filled rows
(with each node's squared norm kept beside it: |x - q|^2 = |x|^2 - 2 x.q + |q|^2,
the last term the same for every node) rather than a Python scan over a list.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.collision_checker import JointConfiguration, JointConfigurations

NO_PARENT = -1
"""Parent index of a root node."""


class ConfigurationTree:
    """Configurations and parent links of a search tree rooted at one configuration."""

    def __init__(self, root: JointConfiguration, initial_capacity: int = 1024) -> None:
        capacity = max(1, initial_capacity)
        self._nodes = np.empty((capacity, root.size), dtype=np.float64)
        self._parents = np.empty(capacity, dtype=np.intp)
        self._squared_norms = np.empty(capacity, dtype=np.float64)
        self._size = 0
        self.add(root, NO_PARENT)

    def __len__(self) -> int:
        return self._size

    @property
    def nodes(self) -> JointConfigurations:
        """A read-only view of the filled node rows, shape (len(self), d)."""
        view = self._nodes[: self._size]
        view.flags.writeable = False
        return view

    def node(self, index: int) -> JointConfiguration:
        """The configuration of node `index` (a copy)."""
        return np.array(self._nodes[index])

    def add(self, q: JointConfiguration, parent: int) -> int:
        """Add a node with the given parent index; return its index."""
        if self._size == len(self._nodes):
            self._grow()
        self._nodes[self._size] = q
        self._parents[self._size] = parent
        self._squared_norms[self._size] = float(q @ q)
        self._size += 1
        return self._size - 1

    def nearest(self, q: JointConfiguration) -> int:
        """Index of the node closest to `q` (Euclidean joint-space distance)."""
        filled = self._size
        return int(np.argmin(self._squared_norms[:filled] - 2.0 * (self._nodes[:filled] @ q)))

    def path_from_root(self, index: int) -> JointConfigurations:
        """Configurations from the root to node `index`, shape (m, d)."""
        chain: list[int] = []
        while index != NO_PARENT:
            chain.append(index)
            index = int(self._parents[index])
        indices: npt.NDArray[np.intp] = np.array(chain[::-1], dtype=np.intp)
        return self._nodes[indices].copy()

    def _grow(self) -> None:
        capacity = 2 * len(self._nodes)
        nodes = np.empty((capacity, self._nodes.shape[1]), dtype=np.float64)
        parents = np.empty(capacity, dtype=np.intp)
        squared_norms = np.empty(capacity, dtype=np.float64)
        nodes[: self._size] = self._nodes[: self._size]
        parents[: self._size] = self._parents[: self._size]
        squared_norms[: self._size] = self._squared_norms[: self._size]
        self._nodes, self._parents, self._squared_norms = nodes, parents, squared_norms
