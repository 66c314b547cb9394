"""``replay.gif``: the whole task seen from a camera that shows the counter and the drawer.

Frames come from PyBullet's tiny renderer with the robot's visual meshes drawn by
lighter copies (`low_poly_meshes`: the same picture at a sixth of the triangles).
What never moves (the counter and whatever is fixed to it) is drawn once, with its
depth; each frame draws only what can move (the robot, the boxes, the drawers) and
keeps, per pixel, whichever of the two is nearer the camera: the picture a full
drawing gives, at a fraction of the pixels filled.
All frames share one palette of 256 colours, chosen from every tenth frame, so
each frame only maps its pixels to it and the encoder stores what changed since
the previous frame (a palette per frame cost four times as long and twice the bytes).
"""

from __future__ import annotations

import io
from collections.abc import Callable
from pathlib import Path

import numpy as np
from PIL import Image as PilImage

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.execute.render.low_poly_meshes import low_poly_copy
from kitchen_tamp.execute.timeline import Timeline
from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.kitchen.show import overview_camera
from kitchen_tamp.world import (
    Body,
    CameraView,
    FloatArray,
    Image,
    LinkVisibility,
    StandIns,
    pixel_window,
    render,
    render_with_depth,
    visual_shapes,
)

MAX_FRAMES = 120
"""Frames in a GIF at most; long runs are shown faster rather than longer."""
MIN_FRAMES = 40
"""Frames in a GIF at least; short runs are sampled more finely."""
FRAME_SECONDS = 0.1
"""How long each frame shows when the run is played at nominal speed."""
PALETTE_FRAME_STRIDE = 10
"""Every this many frames one is looked at to choose the shared palette."""
WINDOW_PADDING = 6
"""Pixels drawn around where the moving things' collision bounds fall (their visuals may reach a
little further than their collision shapes)."""


def frame_times(timeline: Timeline, max_frames: int = MAX_FRAMES, min_frames: int = MIN_FRAMES) -> np.ndarray:
    """Evenly spaced times from start to end: one per ``FRAME_SECONDS``, within the frame limits."""
    count = int(np.clip(np.ceil(timeline.duration / FRAME_SECONDS) + 1, min_frames, max_frames))
    return np.linspace(0.0, timeline.duration, count)


def low_poly_robot(kitchen: KitchenScene) -> StandIns:
    """Stand-ins drawing lighter copies of the robot's OBJ visual meshes in its place."""
    meshes = {
        shape.mesh_path: low_poly_copy(Path(shape.mesh_path))
        for shape in visual_shapes(kitchen.robot.body)
        if shape.mesh_path is not None and shape.mesh_path.lower().endswith(".obj")
    }
    return StandIns(kitchen.robot.body, meshes)


def fixed_links(body: Body) -> set[int]:
    """Indices of ``body``'s links that no movable joint moves (the base is -1)."""
    parents = {joint.index: joint for joint in body.joints}
    fixed = {-1}
    for index in sorted(parents):  # a parent link comes before its children
        joint = parents[index]
        if not joint.movable and joint.parent_index in fixed:
            fixed.add(index)
    return fixed


class LayeredFrames:
    """Frames drawn as a still background (``kitchen``'s fixed links, drawn once) and the
    moving layer (everything else with a visual, the robot's stand-ins included) on top,
    pixel by pixel whichever is nearer."""

    def __init__(self, kitchen: KitchenScene, stand_ins: StandIns, view: CameraView) -> None:
        self.kitchen, self.view = kitchen, view
        others = [body.uid for body in kitchen.scene.bodies if body.uid != kitchen.robot.body.uid]
        self.visibility = LinkVisibility(kitchen.scene.client, [*others, *stand_ins.uids])
        fixed = fixed_links(kitchen.kitchen)
        still = {(kitchen.kitchen.uid, link) for link in fixed}
        self.moving = [link for link in self.visibility.links if link not in still]
        self._moving_bodies = [body for body in kitchen.scene.bodies if body.uid != kitchen.kitchen.uid]
        self._moving_links = [kitchen.kitchen.link_name(index) for index in kitchen.kitchen.link_indices
                              if index not in fixed]
        self.visibility.show_only(still)
        self.background, self.depth = render_with_depth(kitchen.scene, view)
        self.visibility.show_only(self.moving)

    def _moving_bounds(self) -> list[tuple[FloatArray, FloatArray]]:
        """Collision bounds of what can move: the robot (its stand-ins ride on its links), the
        boxes, the kitchen's moving links."""
        bounds = [body.aabb() for body in self._moving_bodies]
        return bounds + [self.kitchen.kitchen.aabb(link) for link in self._moving_links]

    def frame(self) -> Image:
        """The scene as it is now: the background, and the moving layer drawn over the pixels where
        anything moving can show (`pixel_window`), where it is nearer."""
        picture = self.background.copy()
        window = pixel_window(self.kitchen.scene, self.view, self._moving_bounds(), WINDOW_PADDING)
        if window is None:
            return picture
        front, depth = render_with_depth(self.kitchen.scene, self.view, window)
        rows, columns = slice(window.top, window.bottom), slice(window.left, window.right)
        nearer = depth < self.depth[rows, columns]
        picture[rows, columns][nearer] = front[nearer]
        return picture

    def close(self) -> None:
        """Shows every link again."""
        self.visibility.show_only(self.visibility.links)


class ReplayRenderer:
    """What drawing a replay needs before its timeline is known, made from ``kitchen`` (built fresh
    for the problem): the camera, the robot's stand-ins and the still background. A child drawing
    the GIF makes it while the judge is still reading the plan (`background_pictures`)."""

    def __init__(self, kitchen: KitchenScene, width: int = 400, height: int = 300) -> None:
        self.kitchen = kitchen
        self.view = overview_camera(kitchen, width, height)
        self.stand_ins = low_poly_robot(kitchen)
        self.layers = LayeredFrames(kitchen, self.stand_ins, self.view)

    def images(self, timeline: Timeline, on_frame: Callable[[int, int], None] | None = None) -> list[Image]:
        """Pictures of the kitchen along ``timeline`` (once: the kitchen is left at its end); one
        picture of the scene as it is for a timeline without motion (a plan of no actions)."""
        if not timeline.segments:
            self.layers.close()
            return [render(self.kitchen.scene, self.view)]
        times = frame_times(timeline)
        images = []
        for number, _ in enumerate(timeline.play(self.kitchen, times)):
            self.stand_ins.follow()
            images.append(self.layers.frame())
            if on_frame is not None:
                on_frame(number + 1, len(times))
        self.layers.close()
        return images


def render_replay(
    kitchen: KitchenScene,
    timeline: Timeline,
    width: int = 400,
    height: int = 300,
    on_frame: Callable[[int, int], None] | None = None,
) -> list[Image]:
    """Pictures of ``kitchen`` (built fresh for the problem) along ``timeline`` (`ReplayRenderer`)."""
    return ReplayRenderer(kitchen, width, height).images(timeline, on_frame)


def shared_palette(images: list[Image]) -> PilImage.Image:
    """A palette image of 256 colours chosen (fast octree) from every ``PALETTE_FRAME_STRIDE``-th
    frame and the last."""
    chosen = [*images[::PALETTE_FRAME_STRIDE], images[-1]]
    mosaic = PilImage.fromarray(np.ascontiguousarray(np.concatenate(chosen, axis=0)))
    return mosaic.quantize(256, method=PilImage.Quantize.FASTOCTREE, dither=PilImage.Dither.NONE)


def write_gif(path: Path, images: list[Image], seconds_per_frame: float) -> Path:
    """Encode ``images`` as a looping GIF with one shared palette and write it atomically."""
    palette = shared_palette(images)
    frames = [
        PilImage.fromarray(np.ascontiguousarray(image)).quantize(palette=palette, dither=PilImage.Dither.NONE)
        for image in images
    ]
    buffer = io.BytesIO()
    frames[0].save(buffer, format="GIF", save_all=True, append_images=frames[1:],
                   duration=int(1000 * seconds_per_frame), loop=0)
    return write_atomically(path, buffer.getvalue())
