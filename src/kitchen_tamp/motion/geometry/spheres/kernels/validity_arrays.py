"""Every array the validity kernel reads, as one argument: a numba structref.

`sphere_kernel_layout.kernel_arguments` lays the arrays out as a tuple in ``VALIDITY_FIELDS``
order (`sphere_validity_fields`); `validity_arrays` packs such a tuple into a `ValidityArrays`, which
`sphere_kernels.valid_configurations` takes as one argument and unpacks once per call; the
tables the kernel once derived in every call from the arrays (``_derived``) are packed with them.

Why a structref: a compiled call pays for typing and unboxing each argument. Measured with a
trivial body (``python benchmarks/collision.py --dispatch``, CPU, best of five, two runs): 42
arrays passed positionally 2.4-2.8 us a call, one plain tuple of them 3.5-3.9 us, a named tuple
4.9-6.9 us, a jitclass 0.55-1.0 us and a structref 1.0-1.5 us, against 0.18 us for two
arguments. A jitclass's type is new in every process, so numba cannot cache a kernel that takes
one (it would compile for a minute in every run); a structref's type is cached.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
import numpy.typing as npt
from numba.core import types
from numba.experimental import structref

from kitchen_tamp.motion.geometry.spheres.kernels.distance_grid import distance_grid_cells
from kitchen_tamp.motion.geometry.spheres.kernels.tree_walks import STACK_DEPTH
from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import ALL_FIELDS, with_derived

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


@structref.register
class ValidityArraysType(types.StructRef):
    """numba's type of `ValidityArrays`: one field per name of ``VALIDITY_FIELDS``."""

    def preprocess_fields(self, fields: Any) -> tuple[tuple[str, Any], ...]:
        return tuple((name, types.unliteral(kind)) for name, kind in fields)  # type: ignore[no-untyped-call]


class ValidityArrays(structref.StructRefProxy):
    """The validity kernel's arrays as one object (fields in layout order, read in compiled code
    only; their meaning in `sphere_kernels.valid_configurations` and `sphere_kernel_layout`)."""

    lower: FloatArray
    upper: FloatArray
    root: FloatArray
    parents: IntArray
    origins: FloatArray
    kinds: IntArray
    axes: FloatArray
    variables: IntArray
    group_links: IntArray
    group_centers: FloatArray
    group_radii: FloatArray
    group_starts: IntArray
    group_stops: IntArray
    sphere_links: IntArray
    sphere_centers: FloatArray
    sphere_radii: FloatArray
    group_roots: IntArray
    node_links: IntArray
    node_centers: FloatArray
    node_radii: FloatArray
    node_children: IntArray
    node_first: IntArray
    node_last: IntArray
    fine_links: IntArray
    fine_centers: FloatArray
    fine_radii: FloatArray
    box_rotations: FloatArray
    box_centers: FloatArray
    box_halves: FloatArray
    box_kinds: IntArray
    box_lows: FloatArray
    box_highs: FloatArray
    table_variables: IntArray
    table_lows: FloatArray
    table_steps: FloatArray
    table_counts: IntArray
    table_offsets: IntArray
    table_cells: npt.NDArray[np.int8]
    table_margin: float
    group_box_pairs: IntArray
    group_pairs: IntArray
    # Derived by `validity_arrays` from the fields above, so a call need not (`_derived`):
    coarse_local: FloatArray
    low_x: FloatArray
    low_y: FloatArray
    low_z: FloatArray
    high_x: FloatArray
    high_y: FloatArray
    high_z: FloatArray
    unchecked: FloatArray
    group_order: IntArray
    grid_frame: FloatArray
    grid_shape: IntArray
    grid_cells: npt.NDArray[np.uint8]
    origin_axes: IntArray


if tuple(ValidityArrays.__annotations__) != ALL_FIELDS:
    raise ImportError("ValidityArrays' fields are not validity_fields.ALL_FIELDS, in that order")

structref.define_proxy(ValidityArrays, ValidityArraysType, list(ALL_FIELDS))  # type: ignore[no-untyped-call]


@numba.njit(cache=True)
def _pack(fields: tuple[Any, ...]) -> ValidityArrays:
    """``fields`` (in ``ALL_FIELDS`` order) as one `ValidityArrays`. Calling the proxy class from
    Python would compile its constructor again in every process (numba does not cache it: 5-6 s
    of one core a run); this compiled constructor is cached with the kernels."""
    return ValidityArrays(*fields)  # type: ignore[no-untyped-call]


def validity_arrays(arguments: tuple[Any, ...]) -> ValidityArrays:
    """``arguments`` (in ``VALIDITY_FIELDS`` order) as one `ValidityArrays`, with the tables the
    kernel derives from them."""
    packed: ValidityArrays = _pack(with_derived(arguments, distance_grid_cells))
    return packed


ValidityScratch = tuple[Any, ...]
"""What `valid_rows` works in (`validity_scratch`): per-configuration buffers, the stamps saying
when a bound or sphere was last placed, and the last stamp used, so it may serve many calls."""

@numba.njit(cache=True)
def validity_scratch(arrays: ValidityArrays, dimension: int) -> ValidityScratch:
    """Buffers for `valid_rows` on ``arrays``' model with configurations of ``dimension`` joints:
    allocated once, they serve every call a caller makes (a call on one configuration otherwise
    spends more on allocating them than on the check)."""
    nodes = arrays.node_radii.shape[0]
    groups = arrays.group_radii.shape[0]
    return (
        np.zeros(arrays.group_pairs.shape[0], dtype=np.int8),
        np.empty((arrays.parents.shape[0], 3, 4)),
        np.empty((3, 4)),
        np.empty(dimension),
        np.empty(dimension),
        np.empty((groups, 3)),
        np.empty((3, arrays.sphere_radii.shape[0])),
        np.zeros(groups, dtype=np.int64),
        np.empty((3, arrays.fine_radii.shape[0])),
        np.zeros(nodes, dtype=np.int64),
        np.empty((nodes, 3)),
        np.zeros(nodes, dtype=np.int64),
        np.empty(2 * STACK_DEPTH, dtype=np.int64),
        np.empty((2, arrays.table_offsets.shape[0]), dtype=np.int64),
        np.zeros(1, dtype=np.int64),
    )
