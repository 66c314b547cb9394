"""The integer codes the sphere model's kernels read: link kinds and obstacle shapes.

Kept apart from the compiled kernels (``primitives`` and the rest import numba), so that code
laying out the kernels' arrays, or a run served by the kernels compiled ahead of time
(`sphere_kernel_loading`), reads them without importing numba.
"""

from __future__ import annotations

FIXED, REVOLUTE, PRISMATIC = 0, 1, 2
"""Link kinds: fixed to its parent, or moved by a revolute or prismatic joint."""
SKIPPED, REVOLUTE_Z = -1, 3
"""Link kinds only the validity kernel's folded layout has (`sphere_kernel_layout`): a fixed link
folded into its moving ancestor (no pose computed), a revolute joint about its frame's z axis."""
SHAPE_BOX, SHAPE_SPHERE, SHAPE_CYLINDER = 0, 1, 2
"""Obstacle kinds (`sphere_scene.ObstacleBoxes.kinds`): their half extents are a box's, a sphere's
radius thrice, a cylinder's radius twice and half its length (axis z)."""
SHAPE_KINDS = {"box": SHAPE_BOX, "sphere": SHAPE_SPHERE, "cylinder": SHAPE_CYLINDER}
