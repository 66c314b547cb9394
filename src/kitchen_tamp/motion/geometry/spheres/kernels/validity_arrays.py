"""Every array the validity kernel reads, as one argument: a numba structref.

`sphere_kernel_layout.kernel_arguments` lays the arrays out as a tuple in ``VALIDITY_FIELDS``
order; `validity_arrays` packs such a tuple into a `ValidityArrays`, which
`sphere_kernels.valid_configurations` takes as one argument and unpacks once per call.

Why a structref: a compiled call pays for typing and unboxing each argument. Measured with a
trivial body (``python benchmarks/collision.py --dispatch``, best of five, per call): 42 arrays
passed positionally 4.8 us, one plain tuple of them 7.4 us, a named tuple 11.1 us, a jitclass
1.3 us and a structref 1.9 us, against 0.3 us for two arguments. A jitclass's type is new in
every process, so numba cannot cache a kernel that takes one (it would compile for a minute in
every run); a structref's type is cached.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt
from numba.core import types
from numba.experimental import structref

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


VALIDITY_FIELDS = tuple(ValidityArrays.__annotations__)
"""The kernel's arrays by name, in the order `kernel_arguments` lays them out."""

structref.define_proxy(ValidityArrays, ValidityArraysType, list(VALIDITY_FIELDS))  # type: ignore[no-untyped-call]


def validity_arrays(arguments: tuple[Any, ...]) -> ValidityArrays:
    """``arguments`` (in ``VALIDITY_FIELDS`` order) as one `ValidityArrays`."""
    if len(arguments) != len(VALIDITY_FIELDS):
        raise ValueError(f"expected {len(VALIDITY_FIELDS)} kernel arrays, got {len(arguments)}")
    packed: ValidityArrays = ValidityArrays(*arguments)  # type: ignore[no-untyped-call]
    return packed
