"""RRT-Connect's counter-based samples: SplitMix64's outputs, the same bits compiled and in numpy,
one sample at a time as in blocks, and uniform in the box."""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

from kitchen_tamp.motion.sampling.counter_samples import CounterSamples, counter_uniforms
from kitchen_tamp.motion.sampling.rrt_connect_kernel import sample_into

LOWER = np.array([-2.9, -1.8, -2.9, -3.1, -2.9, -0.1, -2.9])
UPPER = np.array([2.9, 1.8, 2.9, 0.0, 2.9, 3.8, 2.9])


def test_the_stream_is_splitmix64() -> None:
    """SplitMix64 from state 0 gives 0xE220A8397B1DCDAF, 0x6E789E6AA1B965F4 first (the reference
    outputs of ``java.util.SplittableRandom``'s generator); a uniform is the top 53 bits."""
    units = counter_uniforms(0, 0, 1, np.zeros(2), np.ones(2))[0]
    expected = [(0xE220A8397B1DCDAF >> 11) * 2.0**-53, (0x6E789E6AA1B965F4 >> 11) * 2.0**-53]
    assert units.tolist() == expected


@numba.njit(cache=True)
def _compiled_samples(seed: int, first: int, count: int, lower: Any, upper: Any) -> Any:
    out = np.empty((count, lower.shape[0]))
    for k in range(count):
        sample_into(seed, first + k, lower, upper, out[k])
    return out


def test_the_compiled_loop_draws_numpys_bits() -> None:
    for seed in (0, 1, 7, 2**40 + 3, 2**63 - 1):
        for first in (0, 13, 2**33):
            expected = counter_uniforms(seed, first, 50, LOWER, UPPER)
            np.testing.assert_array_equal(_compiled_samples(seed, first, 50, LOWER, UPPER), expected)


def test_samples_one_at_a_time_are_the_blocks_values() -> None:
    samples = CounterSamples(LOWER, UPPER, seed=5, block=7)
    one_by_one = np.array([samples.next() for _ in range(30)])
    np.testing.assert_array_equal(one_by_one, counter_uniforms(5, 0, 30, LOWER, UPPER))
    np.testing.assert_array_equal(one_by_one[10:20], counter_uniforms(5, 10, 10, LOWER, UPPER))


def test_samples_fill_the_box_uniformly_and_seeds_differ() -> None:
    drawn = counter_uniforms(3, 0, 20_000, LOWER, UPPER)
    assert np.all(drawn >= LOWER) and np.all(drawn < UPPER)
    units = (drawn - LOWER) / (UPPER - LOWER)
    assert np.allclose(units.mean(axis=0), 0.5, atol=0.01)
    assert np.allclose(units.var(axis=0), 1.0 / 12.0, atol=0.003)
    assert abs(np.corrcoef(units[:-1, 0], units[1:, 0])[0, 1]) < 0.03  # successive samples
    assert abs(np.corrcoef(units[:, 0], units[:, 1])[0, 1]) < 0.03  # joints of one sample
    other = counter_uniforms(4, 0, 20_000, LOWER, UPPER)
    assert abs(np.corrcoef(units[:, 0], (other[:, 0] - LOWER[0]) / (UPPER[0] - LOWER[0]))[0, 1]) < 0.03
