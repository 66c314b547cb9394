"""Headless pictures of a scene with PyBullet's software (tiny) renderer, and stand-in bodies
that draw lighter copies of a body's meshes in its place."""

from __future__ import annotations

import struct
import zlib
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pybullet as p
from numpy.typing import NDArray

from kitchen_tamp.world.bodies import Body
from kitchen_tamp.world.scene import Scene
from kitchen_tamp.world.transforms import FloatArray
from kitchen_tamp.world.visual_shapes import VisualKind, visual_shapes

Image = NDArray[np.uint8]


@dataclass(frozen=True)
class CameraView:
    """A camera looking at ``target`` from ``distance`` at ``yaw``/``pitch`` degrees."""

    target: tuple[float, float, float]
    distance: float
    yaw: float
    pitch: float
    width: int = 640
    height: int = 480
    fov_degrees: float = 50.0
    near: float = 0.05
    far: float = 6.0

    def __post_init__(self) -> None:
        if self.width <= 0 or self.height <= 0 or self.distance <= 0:
            raise ValueError(f"invalid camera view {self}")


@dataclass(frozen=True)
class PixelWindow:
    """Rows ``top`` to ``bottom`` and columns ``left`` to ``right`` (ends excluded) of a picture."""

    top: int
    bottom: int
    left: int
    right: int


def _camera_matrices(scene: Scene, view: CameraView) -> tuple[list[float], list[float]]:
    """PyBullet's view and projection matrices of ``view`` (column-major, as OpenGL's)."""
    view_matrix = p.computeViewMatrixFromYawPitchRoll(
        cameraTargetPosition=view.target,
        distance=view.distance,
        yaw=view.yaw,
        pitch=view.pitch,
        roll=0.0,
        upAxisIndex=2,
        physicsClientId=scene.client,
    )
    projection = p.computeProjectionMatrixFOV(
        fov=view.fov_degrees,
        aspect=view.width / view.height,
        nearVal=view.near,
        farVal=view.far,
        physicsClientId=scene.client,
    )
    return list(view_matrix), list(projection)


def _window_projection(projection: list[float], view: CameraView, window: PixelWindow) -> list[float]:
    """The projection that draws only ``window`` of ``view``'s picture, pixel for pixel: the window's
    normalised device coordinates stretched to the whole viewport (depth unchanged)."""
    left, right = -1.0 + 2.0 * window.left / view.width, -1.0 + 2.0 * window.right / view.width
    top, bottom = 1.0 - 2.0 * window.top / view.height, 1.0 - 2.0 * window.bottom / view.height
    stretch = np.eye(4)
    stretch[0, 0], stretch[0, 3] = 2.0 / (right - left), -(right + left) / (right - left)
    stretch[1, 1], stretch[1, 3] = 2.0 / (top - bottom), -(top + bottom) / (top - bottom)
    matrix = stretch @ np.asarray(projection, dtype=float).reshape(4, 4).T
    return [float(value) for value in matrix.T.ravel()]


def pixel_window(
    scene: Scene, view: CameraView, boxes: Sequence[tuple[FloatArray, FloatArray]], padding: int
) -> PixelWindow | None:
    """The pixels of ``view``'s picture that can show anything inside the axis-aligned ``boxes``
    (lower, upper corners), ``padding`` pixels wider on every side; None when none can, the whole
    picture when a box reaches behind the camera."""
    if not boxes:
        return None
    whole = PixelWindow(0, view.height, 0, view.width)
    view_matrix, projection = _camera_matrices(scene, view)
    camera = np.asarray(projection).reshape(4, 4).T @ np.asarray(view_matrix).reshape(4, 4).T
    corners = np.array([[(low, high)[(k >> axis) & 1][axis] for axis in range(3)] + [1.0]
                        for low, high in boxes for k in range(8)])
    clip = corners @ camera.T
    if np.any(clip[:, 3] <= view.near):
        return whole
    columns = (clip[:, 0] / clip[:, 3] + 1.0) * view.width / 2.0
    rows = (1.0 - clip[:, 1] / clip[:, 3]) * view.height / 2.0
    window = PixelWindow(
        max(0, int(np.floor(rows.min())) - padding),
        min(view.height, int(np.ceil(rows.max())) + padding),
        max(0, int(np.floor(columns.min())) - padding),
        min(view.width, int(np.ceil(columns.max())) + padding),
    )
    if window.bottom <= window.top or window.right <= window.left:
        return None
    return window


def render_with_depth(
    scene: Scene, view: CameraView, window: PixelWindow | None = None
) -> tuple[Image, FloatArray]:
    """An RGB picture (height, width, 3) of the scene seen from ``view`` and its depth buffer
    (height, width; nearer is smaller, 1 where nothing was drawn); with ``window``, only those
    pixels of it, drawn as the whole picture would draw them."""
    scene.require_visuals("rendering a picture")
    view_matrix, projection = _camera_matrices(scene, view)
    width, height = view.width, view.height
    if window is not None:
        projection = _window_projection(projection, view, window)
        width, height = window.right - window.left, window.bottom - window.top
    _, _, rgba, depth, _ = p.getCameraImage(
        width,
        height,
        viewMatrix=view_matrix,
        projectionMatrix=projection,
        renderer=p.ER_TINY_RENDERER,
        flags=p.ER_NO_SEGMENTATION_MASK,
        physicsClientId=scene.client,
    )
    pixels = np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)
    depths = np.asarray(depth, dtype=float).reshape(height, width)
    return np.ascontiguousarray(pixels[:, :, :3]), depths


def render(scene: Scene, view: CameraView) -> Image:
    """An RGB picture (height, width, 3) of the scene seen from ``view``."""
    return render_with_depth(scene, view)[0]


class LinkVisibility:
    """Hides links of bodies from the tiny renderer (which does not draw what has alpha 0) and
    shows them again with each visual's own colour."""

    def __init__(self, client: int, uids: Sequence[int]) -> None:
        self.client = client
        self._colours: dict[tuple[int, int], list[tuple[float, ...]]] = {}
        for uid in uids:
            for data in p.getVisualShapeData(uid, physicsClientId=client):
                self._colours.setdefault((uid, data[1]), []).append(tuple(data[7]))

    @property
    def links(self) -> tuple[tuple[int, int], ...]:
        """Every (body uid, link index) that has a visual."""
        return tuple(self._colours)

    def show_only(self, shown: Collection[tuple[int, int]]) -> None:
        """Shows the links in ``shown`` and hides every other."""
        for (uid, link), colours in self._colours.items():
            visible = (uid, link) in shown
            for index, colour in enumerate(colours):
                rgba = colour if visible else (*colour[:3], 0.0)
                p.changeVisualShape(uid, link, shapeIndex=index, rgbaColor=rgba, physicsClientId=self.client)


class StandIns:
    """Visual-only bodies that draw other mesh files in place of some of ``body``'s mesh visuals
    (``replacements``: a visual's mesh path -> the file drawn instead, at the same scale and
    offset), whose own links are made invisible. ``follow()`` puts each stand-in where its link
    is now; collisions, dynamics and every other body are untouched."""

    def __init__(self, body: Body, replacements: Mapping[str, Path]) -> None:
        self.body = body
        self._links: list[str] = []
        self._uids: list[int] = []
        client = body.client
        for shape in visual_shapes(body):
            replacement = replacements.get(shape.mesh_path or "") if shape.kind is VisualKind.MESH else None
            if replacement is None:
                continue
            visual = p.createVisualShape(
                p.GEOM_MESH,
                fileName=str(replacement),
                meshScale=shape.size,
                visualFramePosition=shape.link_from_visual.position,
                visualFrameOrientation=shape.link_from_visual.quaternion,
                physicsClientId=client,
            )
            self._uids.append(p.createMultiBody(0.0, -1, visual, physicsClientId=client))
            self._links.append(shape.link)
        for link in set(self._links):
            p.changeVisualShape(body.uid, body.link_index(link), rgbaColor=(1.0, 1.0, 1.0, 0.0),
                                physicsClientId=client)
        self.follow()

    @property
    def uids(self) -> tuple[int, ...]:
        """The stand-in bodies."""
        return tuple(self._uids)

    def follow(self) -> None:
        """Place every stand-in at its link's world pose."""
        if not self._links:
            return
        positions, quaternions = self.body.link_frames(self._links)
        for uid, position, quaternion in zip(self._uids, positions, quaternions, strict=True):
            p.resetBasePositionAndOrientation(uid, position, quaternion, physicsClientId=self.body.client)


def tile(images: list[Image], columns: int, gap: int = 4) -> Image:
    """Images of equal size laid out row by row on a white sheet."""
    if not images:
        raise ValueError("nothing to tile")
    height, width, _ = images[0].shape
    rows = (len(images) + columns - 1) // columns
    columns = min(columns, len(images))
    sheet = np.full(
        (rows * height + (rows - 1) * gap, columns * width + (columns - 1) * gap, 3), 255, np.uint8
    )
    for i, image in enumerate(images):
        r, c = divmod(i, columns)
        top, left = r * (height + gap), c * (width + gap)
        sheet[top : top + height, left : left + width] = image
    return sheet


def write_png(image: Image, path: Path | str) -> Path:
    """Save an RGB image (height, width, 3) as a PNG file (no imaging library needed)."""
    pixels = np.ascontiguousarray(image, dtype=np.uint8)
    if pixels.ndim != 3 or pixels.shape[2] != 3:
        raise ValueError(f"expected an RGB image, got shape {pixels.shape}")
    height, width, _ = pixels.shape
    raw = b"".join(b"\x00" + pixels[row].tobytes() for row in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(raw, 6))
        + chunk(b"IEND", b"")
    )
    return out
