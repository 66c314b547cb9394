from __future__ import annotations

from pathlib import Path

import imageio.v2 as imageio
import numpy as np

from kitchen_tamp.world import CameraView, Robot, Scene, render, tile, write_png


def test_render_and_write_png(panda_scene: tuple[Scene, Robot], tmp_path: Path) -> None:
    scene, _ = panda_scene
    image = render(scene, CameraView((0.5, 0.0, 0.5), 2.0, yaw=-60, pitch=-30, width=96, height=64))
    assert image.shape == (64, 96, 3) and image.dtype == np.uint8
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 5
    sheet = tile([image, image, image], columns=2)
    path = write_png(sheet, tmp_path / "sheet.png")
    assert np.array_equal(imageio.imread(path)[:, :, :3], sheet)
