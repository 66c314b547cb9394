"""Tight sphere coverings of convex shapes, proved by code: the fine level of the sphere model.

Candidate spheres are centred on a grid inside the shape, each with the radius
that reaches exactly ``tolerance`` outside it (its depth under the nearest face
plus the tolerance; for a centre inside a convex shape that is exactly how far
the ball reaches out). A greedy set cover of sampled points picks among them;
`verify_covering` then proves the union covers the whole shape: the shape's
bounding box is cut into cubes, each cube's part of the shape is clipped
exactly, and its vertices must all lie in one sphere (a convex piece inside a
ball when its vertices are). A piece no sphere holds is split in eight; at the
finest level the sphere needing least growth grows to hold it.

Tighter than `sphere_covering.cover_with_spheres` (a few millimetres against a
centimetre or two) at ten times the spheres, so the kernel opens it only where
the coarse covering finds a pair closer than the margin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from kitchen_tamp.motion.geometry.spheres.covering import (
    ConvexPolytope,
    SphereSet,
    box_polytope,
    depth_below_faces,
    overshoot,
    sample_polytope,
)

FloatArray = npt.NDArray[np.float64]

TIGHT_COVERING_TOLERANCE = 0.004
"""How far (m) each fine sphere reaches outside the shape it covers."""
TIGHT_MAX_SPHERES = 320
"""Fine spheres per shape at most (the tolerance is relaxed until they fit)."""
SAMPLE_SLACK = 0.2
"""Sampled points are chosen to lie this fraction of the tolerance inside their sphere, so that
the gaps between samples are mostly covered too (the verification grows spheres where not)."""
_PLANE_EPSILON = 1e-12


def _candidate_spheres(
    polytope: ConvexPolytope, planes: tuple[FloatArray, FloatArray], tolerance: float
) -> tuple[FloatArray, FloatArray]:
    """Centres on a grid inside the polytope, each with the radius that reaches exactly
    ``tolerance`` outside (its depth plus the tolerance)."""
    vertices = polytope.vertices
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    spacing = min(1.5 * tolerance, float(np.min(high - low)) / 6.0)
    axes = [np.arange(low[k] + spacing / 2.0, high[k], spacing) for k in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    depth = depth_below_faces(grid, planes)
    inside = depth > 0.0
    return grid[inside], depth[inside] + tolerance


def _greedy_cover(centers: FloatArray, radii: FloatArray, points: FloatArray) -> list[int]:
    """Candidates chosen greedily (most points not yet covered first) until every point is covered
    or no candidate covers another."""
    # Point by candidate, so that the candidates covering the newly covered points are whole rows.
    covered_by = np.zeros((len(points), len(centers)), dtype=bool)
    for start in range(0, len(points), 256):
        chunk = slice(start, start + 256)
        squared = np.sum((points[chunk, None, :] - centers[None]) ** 2, axis=2)
        covered_by[chunk] = squared <= radii[None] ** 2
    counts = np.count_nonzero(covered_by, axis=0)
    uncovered = np.ones(len(points), dtype=bool)
    chosen: list[int] = []
    while uncovered.any():
        best = int(np.argmax(counts))
        if counts[best] == 0:
            break
        chosen.append(best)
        newly = covered_by[:, best] & uncovered
        uncovered &= ~newly
        counts -= covered_by[newly].sum(axis=0, dtype=np.int64)
    return chosen


@dataclass(frozen=True)
class CoveringReport:
    """What verifying a covering found: cells checked, spheres grown to hold a cell, and the worst
    overshoot (m) after growing."""

    cells: int
    grown: int
    worst_overshoot: float


OUTER_FACES = 1
"""Faces a cell is first clipped by (see `verify_covering`): one measured fastest (25.5 s for the
Panda's first three meshes, against 26.1 s with two, 27.5 s with three and 37.7 s before)."""
UNIT_CUBE_CORNERS = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)


def _cell_pieces(
    polytope: ConvexPolytope,
    planes: tuple[FloatArray, FloatArray],
    low: FloatArray,
    size: float,
    corners: FloatArray,
    sides: FloatArray,
    faces: int | None = None,
) -> FloatArray | None:
    """Vertices of the part of the polytope in the cube at ``low`` with edge ``size`` (None if
    empty), given the cube's ``corners`` and their signed distances ``sides`` to the faces.

    With ``faces``, the cube is clipped only by that many of the faces cutting it (those its
    corners lie furthest outside): a piece that holds the true one."""
    normals, offsets = planes
    cut = np.flatnonzero(np.any(sides > _PLANE_EPSILON, axis=0))
    if len(cut) == 0:
        return corners  # the cube lies inside the polytope: it is the piece
    if faces is not None:
        cut = cut[np.argsort(-sides[:, cut].max(axis=0), kind="stable")[:faces]]
    piece: ConvexPolytope | None = box_polytope(np.full(3, size)).transformed(_translation(low + size / 2.0))
    for face in cut:
        if piece is None:
            return None
        piece = piece.clipped(normals[face], float(offsets[face]))
    return None if piece is None else piece.vertices


def _farthest_point_distances(points: FloatArray, centers: FloatArray) -> FloatArray:
    """Per centre, the distance to the farthest of ``points``: the radius a sphere there needs to
    hold them all."""
    distances: FloatArray = np.linalg.norm(points[:, None, :] - centers[None], axis=2)
    farthest: FloatArray = distances.max(axis=0)
    return farthest


def _translation(offset: FloatArray) -> FloatArray:
    pose = np.eye(4)
    pose[:3, 3] = offset
    return pose


def verify_covering(
    polytope: ConvexPolytope, spheres: SphereSet, cell_size: float, depth: int = 3
) -> tuple[SphereSet, CoveringReport]:
    """Proves the covering: the polytope's bounding box is cut into cubes, each cube's part of the
    polytope (a convex piece, clipped exactly) must lie in one sphere, i.e. all its vertices must.
    A piece no sphere holds is split in eight, down to ``depth`` halvings; a piece still not held
    grows the sphere that needs the least growth to hold it. The pieces make up the polytope, so
    the returned spheres cover it."""
    planes = polytope.planes()
    centers, radii = spheres.centers, spheres.radii.copy()
    vertices = polytope.vertices
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    counts = np.maximum(1, np.ceil((high - low) / cell_size).astype(int))
    stack = [
        (low + cell_size * np.array([i, j, k], dtype=float), cell_size, 0)
        for i in range(counts[0])
        for j in range(counts[1])
        for k in range(counts[2])
    ]
    cells = grown = 0
    face_normals, face_offsets = planes
    while stack:
        corner, size, level = stack.pop()
        corners = corner + size * UNIT_CUBE_CORNERS
        sides = corners @ face_normals.T - face_offsets[None]
        if np.any(np.all(sides > _PLANE_EPSILON, axis=0)):
            continue  # the cube lies outside a face: no piece
        cells += 1
        # A ball holding the cube's corners holds the cube, and so the piece: no clipping needed.
        if np.any(_farthest_point_distances(corners, centers) <= radii):
            continue
        # The cube clipped by its deepest-cutting face alone holds the piece: when a ball holds that,
        # it holds the piece, at one clip instead of one per cutting face. The verdicts (and so the
        # spheres) are those of clipping every cell fully; only the work is less.
        outer = _cell_pieces(polytope, planes, corner, size, corners, sides, faces=OUTER_FACES)
        if outer is not None and np.any(_farthest_point_distances(outer, centers) <= radii):
            continue
        piece = _cell_pieces(polytope, planes, corner, size, corners, sides)
        if piece is None:
            cells -= 1
            continue
        needed = _farthest_point_distances(piece, centers)
        if np.any(needed <= radii):
            continue
        if level < depth:
            half = size / 2.0
            offsets = half * np.array(
                [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float
            )
            stack += [(corner + offset, half, level + 1) for offset in offsets]
            continue
        nearest = int(np.argmin(needed - radii))
        radii[nearest] = needed[nearest] * (1.0 + 1e-12)
        grown += 1
    worst = max((overshoot(c, r, planes) for c, r in zip(centers, radii, strict=True)), default=0.0)
    return SphereSet(centers.copy(), radii), CoveringReport(cells, grown, worst)


def cover_tightly(
    polytope: ConvexPolytope,
    tolerance: float = TIGHT_COVERING_TOLERANCE,
    max_spheres: int = TIGHT_MAX_SPHERES,
) -> SphereSet:
    """Spheres whose union covers ``polytope``, each reaching about ``tolerance`` outside it.

    Candidates centred on a grid inside reach exactly ``tolerance`` outside; a greedy set cover of
    sampled points (vertices, faces, inside) picks among them; `verify_covering` then proves the
    union covers the whole polytope, growing a sphere where a gap between samples needs it. Past
    ``max_spheres`` the tolerance is relaxed by half again until it fits."""
    planes = polytope.planes()
    points = sample_polytope(polytope, 3000, np.random.default_rng(0))
    while True:
        centers, radii = _candidate_spheres(polytope, planes, tolerance)
        chosen = _greedy_cover(centers, radii - SAMPLE_SLACK * tolerance, points)
        if len(chosen) <= max_spheres:
            break
        tolerance *= 1.5
    greedy = SphereSet(centers[chosen], radii[chosen])
    covered, _ = verify_covering(polytope, greedy, cell_size=4.0 * tolerance)
    return covered
