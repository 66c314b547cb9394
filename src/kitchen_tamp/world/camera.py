"""Headless pictures of a scene with PyBullet's software (tiny) renderer."""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pybullet as p
from numpy.typing import NDArray

from kitchen_tamp.world.scene import Scene

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


def render(scene: Scene, view: CameraView) -> Image:
    """An RGB picture (height, width, 3) of the scene seen from ``view``."""
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
    _, _, rgba, _, _ = p.getCameraImage(
        view.width,
        view.height,
        viewMatrix=view_matrix,
        projectionMatrix=projection,
        renderer=p.ER_TINY_RENDERER,
        physicsClientId=scene.client,
    )
    pixels = np.asarray(rgba, dtype=np.uint8).reshape(view.height, view.width, 4)
    return np.ascontiguousarray(pixels[:, :, :3])


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
