"""The sphere model's compiled (numba) kernels.

- ``validity``: `valid_configurations`, per configuration forward kinematics, then the
  sphere trees against the boxes and against each other;
- ``clearance``: `clearance_penalties`, a smooth clearance value and its gradient;
- ``primitives`` and ``tree_walks``: what both share (placing spheres, walking trees);
- ``layout``: the arrays the kernels take, built from a `SphereScene`;
- ``segments``: a joint-space segment checked in one call, its batches screened eight
  configurations at a time in SIMD lanes (``lanes``) before the validity kernel sees them.
"""
