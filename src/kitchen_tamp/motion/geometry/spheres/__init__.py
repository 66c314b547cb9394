"""The sphere model: the robot as spheres on its links, checked against the scene's boxes.

Spheres come from code, not by hand: ``covering`` (coarse level) and
``tight_covering`` (fine level) cover each collision shape with spheres and
prove it. ``scene`` places them on a ``kinematics`` tree read from the URDF;
``kernels`` holds the compiled (numba) validity and clearance kernels;
``pair_tables`` settles self-collision pairs ahead of time. What other code uses:

- `SphereCollisionChecker` (``checker``): batched validity, segments, signed distances;
- `SphereScreenedChecker` (``screening``): spheres accept, an exact model decides the rest;
- `EndConfirmedChecker` (``screening``): spheres throughout, an exact model deciding near a start
  or goal within the spheres' overshoot of an obstacle;
- `SphereClearance` (``clearance``): one smooth clearance value per configuration, for
  trajectory optimisation.

The model's internals are described in ``docs/sphere-model.md``.
"""

from kitchen_tamp.motion.geometry.spheres.checker import SphereCollisionChecker
from kitchen_tamp.motion.geometry.spheres.clearance import SphereClearance
from kitchen_tamp.motion.geometry.spheres.scene import PYBULLET_MESH_MARGIN, SphereScene
from kitchen_tamp.motion.geometry.spheres.screening import EndConfirmedChecker, SphereScreenedChecker
from kitchen_tamp.motion.geometry.spheres.stored_spheres import sphere_cache_directory

__all__ = [
    "PYBULLET_MESH_MARGIN",
    "EndConfirmedChecker",
    "SphereClearance",
    "SphereCollisionChecker",
    "SphereScene",
    "SphereScreenedChecker",
    "sphere_cache_directory",
]
