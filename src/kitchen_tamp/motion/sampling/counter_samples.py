"""Random samples as a function of (seed, index): a counter-based stream, SplitMix64's (RRT-Connect's
samples, and the shortcut's tries from far along the same stream).

Sample ``k`` of a seed is computed from ``k`` alone, so the compiled loop (`rrt_connect_kernel`)
draws each iteration's sample in the iteration, with no generator to create in Python and no block
of samples handed in, and the Python loop draws the very same values here (`CounterSamples`).
A query is then one compiled call, where creating numpy's generator cost a cold query 65 us, more
than a tenth of one on MotionBenchMaker's tables (docs/motion.md, "One compiled call a query").

SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014;
``java.util.SplittableRandom``) steps its state by a fixed odd constant and returns the state
through a finaliser, so its ``n``-th output is the finaliser of ``key + n * GAMMA``: a counter-based
generator. The seed (a non-negative integer below 2^63, `checked_seed`) is the starting state, as
``SplittableRandom(seed)`` takes it: seeds next to each other give unrelated streams through the
finaliser. A uniform is the output's top 53 bits over 2^53, as numpy draws doubles.

`counter_uniforms` is written in numpy's array operations on ``uint64`` (which wrap), for the Python
loop and the shortcut's tries. The compiled loop draws each sample one output at a time from the
same constants (`rrt_connect_kernel.sample_into`, tested to give these bits): numba compiles these
array operations too, but into 4,000 instructions and 200 ns a sample, the arrays' allocations.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.collision_checker import JointConfiguration, JointConfigurations

GAMMA = np.uint64(0x9E3779B97F4A7C15)
"""SplitMix64's step: the odd integer nearest 2^64 over the golden ratio."""
MIX_FIRST = np.uint64(0xBF58476D1CE4E5B9)
MIX_SECOND = np.uint64(0x94D049BB133111EB)
UNIT = 2.0**-53


def checked_seed(seed: int) -> int:
    """``seed``, when it names a stream (a non-negative integer below 2^63), else a ValueError."""
    if not 0 <= seed < 2**63:
        raise ValueError(f"seed must be a non-negative integer below 2^63, got {seed}")
    return seed


def counter_uniforms(
    seed: int,
    first: int,
    count: int,
    lower: npt.NDArray[np.float64],
    upper: npt.NDArray[np.float64],
) -> JointConfigurations:
    """Samples ``first`` .. ``first + count - 1`` of the stream of ``seed`` in the box (lower, upper), shape
    (count, d): joint ``j`` of sample ``k`` is ``lower + (upper - lower) u`` with ``u`` the stream's
    output ``k d + j`` as a uniform in [0, 1)."""
    dimension = lower.shape[0]
    counters = np.arange(first * dimension, (first + count) * dimension).astype(np.uint64)
    bits = np.uint64(seed) + (counters + np.uint64(1)) * GAMMA
    bits = (bits ^ (bits >> np.uint64(30))) * MIX_FIRST  # the finaliser (Stafford's "Mix13")
    bits = (bits ^ (bits >> np.uint64(27))) * MIX_SECOND
    bits = bits ^ (bits >> np.uint64(31))
    units = (bits >> np.uint64(11)).astype(np.float64) * UNIT
    return lower + (upper - lower) * units.reshape(count, dimension)


class CounterSamples:
    """The stream of ``seed`` in the box (lower, upper), one sample at a time (as the Python loop
    takes them), drawn a block at a time."""

    def __init__(
        self, lower: npt.NDArray[np.float64], upper: npt.NDArray[np.float64], seed: int, block: int = 64
    ) -> None:
        self._lower, self._upper, self._block = lower, upper, block
        self._seed = seed
        self._drawn = np.empty((0, lower.shape[0]))
        self._first = 0
        self._next = 0

    def next(self) -> JointConfiguration:
        """The next sample (a fresh array)."""
        if self._next == self._drawn.shape[0]:
            self._first += self._drawn.shape[0]
            self._drawn = counter_uniforms(self._seed, self._first, self._block, self._lower, self._upper)
            self._next = 0
        self._next += 1
        sample: JointConfiguration = self._drawn[self._next - 1].copy()
        return sample
