"""Eight configurations at once in SIMD lanes: a screen in front of the validity kernel.

- ``simd``: `Doubles8`, LLVM's ``<8 x double>`` as a numba type, with its arithmetic, comparisons
  into bit masks, and gathers;
- ``kinematics``: sines, cosines and link poses of eight configurations;
- ``buffers``: `LaneBuffers`, what the screen works in, as one argument;
- ``screen``: `first_invalid_in_lanes`, which clears the configurations the kernel would accept and
  leaves the rest to it.
"""
