"""What a call into the sphere model's compiled kernel costs before any geometry, and what a
segment check costs as one compiled call against batches of rows (``collision.py --dispatch``).

1. Dispatch: numba types and unboxes every argument of every call. Five functions with the same
   trivial body take the validity kernel's 42 arrays positionally, as one tuple, as a named
   tuple, as a jitclass and as a structref (what the kernel takes: `ValidityArrays`); CPU
   microseconds per call, best of five rounds, beside a call with two arguments.
2. The kernel itself on the kitchen's free-hand scene: one configuration and 16 per call.
3. Segment checks of random kitchen segments (0.01 rad, as planning checks them): the sphere
   model's compiled segment check (`sphere_segments`: one call, stopping at the first collision)
   against the same model asked batch by batch through ``is_valid`` (how every other checker is
   asked); verdicts and counts must agree.
"""

from __future__ import annotations

import collections
import time
from collections.abc import Callable
from typing import Any

import numba
import numpy as np
import numpy.typing as npt
from numba.core import types
from numba.experimental import jitclass, structref

from kitchen_tamp.motion import CountingSegmentChecker
from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.kernels.validity_fields import VALIDITY_FIELDS

FloatArray = npt.NDArray[np.float64]
ARRAYS = 42


def _best_us(function: Callable[[], object], calls: int) -> float:
    function()
    best = np.inf
    for _ in range(5):
        start = time.process_time()
        for _ in range(calls):
            function()
        best = min(best, (time.process_time() - start) / calls)
    return best * 1e6


def _dispatch_variants() -> dict[str, Callable[[], object]]:
    names = [f"a{i}" for i in range(ARRAYS)]
    arrays = [np.zeros(10) for _ in names]
    q = np.zeros(7)
    scope: dict[str, Any] = {"numba": numba}
    body = f"return q[0] + a0[0] + a{ARRAYS - 1}[0] + m"
    exec(f"@numba.njit\ndef positional(q, {', '.join(names)}, m):\n    {body}", scope)  # 44 parameters
    positional = scope["positional"]

    @numba.njit
    def two(q: FloatArray, m: float) -> float:
        return q[0] + m

    @numba.njit
    def in_tuple(q: FloatArray, t: Any, m: float) -> float:
        return q[0] + t[0][0] + t[ARRAYS - 1][0] + m

    @numba.njit
    def by_attribute(q: FloatArray, t: Any, m: float) -> float:
        return q[0] + t.a0[0] + t.a41[0] + m

    named = collections.namedtuple("named", names)  # type: ignore[misc]

    @jitclass([(n, numba.float64[::1]) for n in names])
    class Held:
        def __init__(self) -> None:
            pass

    held = Held()
    for name, array in zip(names, arrays, strict=True):
        setattr(held, name, array)

    class ProxyType(types.StructRef):
        pass

    class Proxy(structref.StructRefProxy):  # type: ignore[misc]
        pass

    structref.register(ProxyType)
    structref.define_proxy(Proxy, ProxyType, names)  # type: ignore[no-untyped-call]
    proxy = Proxy(*arrays)
    packed, named_packed = tuple(arrays), named(*arrays)
    return {
        "two arguments": lambda: two(q, 0.0),
        f"{ARRAYS} arrays positionally": lambda: positional(q, *arrays, 0.0),
        "one tuple": lambda: in_tuple(q, packed, 0.0),
        "one named tuple": lambda: by_attribute(q, named_packed, 0.0),
        "one jitclass (not cacheable)": lambda: by_attribute(q, held, 0.0),
        "one structref": lambda: by_attribute(q, proxy, 0.0),
    }


def dispatch_report(checker: SphereCollisionChecker, seed: int) -> str:
    """The three measurements above, as lines."""
    lines = [f"call dispatch, trivial body ({len(VALIDITY_FIELDS)} kernel arrays), CPU us per call:"]
    lines += [f"  {name:<32}{_best_us(call, 20000):>7.2f}" for name, call in _dispatch_variants().items()]
    rng = np.random.default_rng(seed)
    one = np.ascontiguousarray(rng.uniform(checker.lower, checker.upper, size=(1, 7)))
    sixteen = np.ascontiguousarray(rng.uniform(checker.lower, checker.upper, size=(16, 7)))
    lines.append(
        f"the validity kernel (kitchen, free hand), CPU us per call: 1 configuration "
        f"{_best_us(lambda: checker.is_valid(one), 5000):.2f}, 16 configurations "
        f"{_best_us(lambda: checker.is_valid(sixteen), 5000):.2f}"
    )
    lines.append(_segment_line(checker, rng))
    return "\n".join(lines)


class _RowsOnly:
    """The sphere model asked through ``is_valid`` alone."""

    def __init__(self, checker: SphereCollisionChecker) -> None:
        self.checker = checker

    def is_valid(self, qs: FloatArray) -> npt.NDArray[np.bool_]:
        return self.checker.is_valid(qs)

    def segment_valid(self, q0: FloatArray, q1: FloatArray) -> bool:
        raise NotImplementedError


def _segment_line(checker: SphereCollisionChecker, rng: np.random.Generator) -> str:
    starts = rng.uniform(checker.lower, checker.upper, size=(400, 7))
    ends = starts + rng.uniform(-0.5, 0.5, size=(400, 7))
    ends = np.clip(ends, checker.lower, checker.upper)
    results: list[tuple[list[bool], int]] = []
    costs = [np.inf, np.inf]
    for _ in range(3):  # alternating, best of three (the first also loads the compiled code)
        results = []
        for k, target in enumerate((checker, _RowsOnly(checker))):
            segments = CountingSegmentChecker(target, 0.01)
            start = time.process_time()
            verdicts = [segments.segment_valid(a, b) for a, b in zip(starts, ends, strict=True)]
            costs[k] = min(costs[k], (time.process_time() - start) / len(starts) * 1e6)
            results.append((verdicts, segments.configurations_checked))
    agree = "same verdicts and counts" if results[0] == results[1] else "DIFFERENT verdicts or counts"
    return (
        f"segment checks ({len(starts)} random segments of up to 1.3 rad, {sum(results[0][0])} free), CPU us "
        f"per segment: one compiled call {costs[0]:.1f}, batches through is_valid {costs[1]:.1f} "
        f"({costs[1] / costs[0]:.1f}x); {agree}"
    )
