"""What the screen works in, as one argument: a numba structref of its buffers.

A compiled function counts a reference to each array it is passed on entry and drops it on exit
(numba's ``NRT_incref``/``NRT_decref``, each an atomic add behind a call); numba prunes the pair
when nothing between could drop the array, which it does not prove across a loop or a branch. With
the buffers as a tuple of eight arrays, each step of the screen (the tables, the obstacles, the
self pairs) paid sixteen such calls a chunk of lanes. A structref is one reference, and a field
read where it is used is counted and dropped in one basic block, where the pair is pruned.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
import numpy.typing as npt
from numba.core import types
from numba.experimental import structref

from kitchen_tamp.motion.geometry.spheres.kernels.lanes.kinematics import LANES
from kitchen_tamp.motion.geometry.spheres.kernels.validity_arrays import ValidityArrays

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


@structref.register
class LaneBuffersType(types.StructRef):
    """numba's type of `LaneBuffers`."""

    def preprocess_fields(self, fields: Any) -> tuple[tuple[str, Any], ...]:
        return tuple((name, types.unliteral(kind)) for name, kind in fields)  # type: ignore[no-untyped-call]


class LaneBuffers(structref.StructRefProxy):
    """The screen's buffers, lane innermost (`kinematics`): the lanes' joint values, sines and
    cosines, link poses and group bounds; the rows left to the kernel and their indices; and per
    self pair, the lanes its table proves clear."""

    values: FloatArray
    sines: FloatArray
    cosines: FloatArray
    poses: FloatArray
    group_world: FloatArray
    left: FloatArray
    left_rows: IntArray
    proved: IntArray


FIELDS = ("values", "sines", "cosines", "poses", "group_world", "left", "left_rows", "proved")
structref.define_proxy(LaneBuffers, LaneBuffersType, list(FIELDS))  # type: ignore[no-untyped-call]


@numba.njit(cache=True)
def lane_buffers(arrays: ValidityArrays, dimension: int) -> LaneBuffers:
    """Buffers for `screen.first_invalid_in_lanes` on ``arrays``' model, configurations of
    ``dimension`` joints."""
    links, groups = arrays.parents.shape[0], arrays.group_radii.shape[0]
    return LaneBuffers(  # type: ignore[no-untyped-call]
        np.empty(dimension * LANES),
        np.empty(dimension * LANES),
        np.empty(dimension * LANES),
        np.empty(links * 12 * LANES),
        np.empty(groups * 3 * LANES),
        np.empty((LANES, dimension)),
        np.empty(LANES, dtype=np.int64),
        np.empty(arrays.group_pairs.shape[0], dtype=np.int64),
    )
