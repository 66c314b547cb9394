"""Planning-time geometry models of a described scene, each a `CollisionChecker`.

A model is built from a `DescribedScene` (``described_scene``: plain names, URDF
paths, poses and the pairs to check) and answers batched validity queries and
signed distances:

- ``drake``: Drake's MultibodyPlant and SceneGraph, exact for convex hulls
  (`DrakeCollisionChecker`); importing it loads Drake.
- ``spheres``: the robot as spheres proved to cover its meshes, checked by a
  compiled kernel (`SphereCollisionChecker`), fastest; ``spheres.screening``
  puts it in front of an exact model.
- ``urdf``: the parts of a URDF both read (link tree, joints, collision shapes).

This face imports neither Drake nor numba: import the model you use.
"""

from kitchen_tamp.motion.geometry.described_scene import (
    DEFAULT_DISTANCE_HORIZON,
    DescribedAttachment,
    DescribedBody,
    DescribedPair,
    DescribedScene,
)

__all__ = [
    "DEFAULT_DISTANCE_HORIZON",
    "DescribedAttachment",
    "DescribedBody",
    "DescribedPair",
    "DescribedScene",
]
