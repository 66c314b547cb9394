"""``replay.html``: a run in the browser, orbitable, with a time slider, in one file.

Drake's Meshcat draws the visuals of a ``SceneRecording`` (the primitives, meshes
and colours of the URDFs the simulator loaded), animates each link through the
recorded world poses, and exports the scene and the animation with Meshcat's
JavaScript as one self-contained page (``Meshcat.StaticHtml``): nothing is fetched
from the network when it is opened. The same drawing serves the live viewer
(``--meshcat``), which shows the scene while a run plans.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.geometry import Box, Capsule, Cylinder, Mesh, Meshcat, Rgba, Shape, Sphere
from pydrake.math import RigidTransform

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.execute.render.scene_recording import RecordedLink, SceneRecorder, SceneRecording
from kitchen_tamp.execute.render.untextured_meshes import untextured_obj_mesh
from kitchen_tamp.execute.timeline import Timeline
from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.kitchen.show import overview_camera
from kitchen_tamp.world import CameraView, FloatArray, Pose, VectorLike, VisualKind, VisualShape

HTML_FILE = "replay.html"
MAX_FRAMES_PER_SECOND = 30
"""Frames per second of a replay at most (Meshcat interpolates between them)."""
MAX_FRAMES = 900
"""Frames in a replay at most; longer runs get a lower frame rate, so the page stays small."""
SCENE_PATH = "/kitchen_tamp"
"""Meshcat path under which the scene is drawn."""
MESHCAT_FOV_DEGREES = 75.0
"""Meshcat's default camera field of view (vertical, degrees)."""
CAMERA_MARGIN = 1.25
"""How much farther than the GIF's camera (corrected for the field of view) the page's camera starts."""
_POSE_TOLERANCE = 1e-7
"""Pose change (m, or quaternion component) below which a link counts as still."""


def replay_frame_rate(duration: float) -> int:
    """Frames per second for a replay of ``duration`` seconds: at most ``MAX_FRAMES_PER_SECOND``,
    and at most ``MAX_FRAMES`` frames in all."""
    if duration <= 0.0:
        return MAX_FRAMES_PER_SECOND
    return int(np.clip(np.floor((MAX_FRAMES - 1) / duration), 1, MAX_FRAMES_PER_SECOND))


def replay_frame_times(duration: float) -> FloatArray:
    """Frame times from 0 to ``duration`` at ``replay_frame_rate(duration)``, the end included."""
    step = 1.0 / replay_frame_rate(duration)
    times = np.arange(0.0, duration, step)
    return np.append(times, duration) if duration - times[-1] > 1e-9 else times


def record_timeline(kitchen: KitchenScene, timeline: Timeline) -> SceneRecording:
    """Pose ``kitchen`` (as built for the problem) along ``timeline`` and record every frame;
    the kitchen is left as it was."""
    recorder = SceneRecorder(kitchen.scene)
    with kitchen.scene.preserved():
        for time_s, _ in timeline.play(kitchen, replay_frame_times(timeline.duration)):
            recorder.capture(time_s)
    return recorder.recording()


def _shape(visual: VisualShape) -> Shape:
    sx, sy, sz = visual.size
    if visual.kind is VisualKind.BOX:
        return Box(sx, sy, sz)
    if visual.kind is VisualKind.SPHERE:
        return Sphere(sx)
    if visual.kind is VisualKind.CYLINDER:
        return Cylinder(sy, sx)
    if visual.kind is VisualKind.CAPSULE:
        return Capsule(sy, sx)
    if visual.mesh_path is None:
        raise ValueError(f"mesh visual of link {visual.link!r} has no file")
    if visual.mesh_path.lower().endswith(".obj"):
        return Mesh(untextured_obj_mesh(visual.mesh_path), sx)
    return Mesh(Path(visual.mesh_path), sx)


def _transform(position: VectorLike, quaternion: VectorLike) -> RigidTransform:
    x, y, z, w = (float(v) for v in quaternion)
    return RigidTransform(Quaternion(w=w, x=x, y=y, z=z), np.asarray(position, dtype=float))  # type: ignore[arg-type]


def _pose_transform(pose: Pose) -> RigidTransform:
    return _transform(pose.position, pose.quaternion)


def link_path(link: RecordedLink) -> str:
    """Meshcat path of a recorded link's frame."""
    return f"{SCENE_PATH}/{link.body}/{link.link}"


def camera_eye(view: CameraView) -> FloatArray:
    """Where to put Meshcat's camera to see what the PyBullet yaw/pitch/distance camera ``view``
    sees (z up): on the same line of sight, at the distance where Meshcat's wider field of view
    shows as much, with ``CAMERA_MARGIN`` to spare."""
    yaw, pitch = np.radians(view.yaw), np.radians(view.pitch)
    zoom = np.tan(np.radians(view.fov_degrees / 2)) / np.tan(np.radians(MESHCAT_FOV_DEGREES / 2))
    distance = CAMERA_MARGIN * view.distance * zoom
    offset = distance * np.array(
        [np.cos(pitch) * np.sin(yaw), -np.cos(pitch) * np.cos(yaw), -np.sin(pitch)]
    )
    eye: FloatArray = np.asarray(view.target, dtype=float) + offset
    return eye


@contextmanager
def _quiet_drake() -> Iterator[None]:
    """Drake's log below warnings stays silent (Meshcat announces every server it starts)."""
    logger = logging.getLogger("drake")
    level = logger.level
    logger.setLevel(max(level, logging.WARNING))
    try:
        yield
    finally:
        logger.setLevel(level)


class SceneViewer:
    """A Meshcat viewer with the links of a scene drawn in it: a web server on this machine
    (``port``: 0 for any free one, None for the first free from 7000) while it lives."""

    def __init__(
        self, links: tuple[RecordedLink, ...], camera: CameraView | None = None, port: int | None = 0
    ) -> None:
        with _quiet_drake():
            self.meshcat = Meshcat(port)
        self.links = links
        for link in links:
            for number, visual in enumerate(link.visuals):
                path = f"{link_path(link)}/visual{number}"
                self.meshcat.SetObject(path, _shape(visual), Rgba(*visual.rgba))
                self.meshcat.SetTransform(path, _pose_transform(visual.link_from_visual))
        if camera is not None:
            target = np.asarray(camera.target, dtype=float)
            self.meshcat.SetCameraPose(camera_eye(camera), target)  # type: ignore[arg-type]

    @property
    def url(self) -> str:
        """Where a browser on this machine sees the viewer."""
        return str(self.meshcat.web_url())

    def show(self, positions: FloatArray, quaternions: FloatArray) -> None:
        """Put every link at the given world poses (one row per link) now."""
        for index, link in enumerate(self.links):
            self.meshcat.SetTransform(link_path(link), _transform(positions[index], quaternions[index]))

    def animate(self, recording: SceneRecording) -> None:
        """Replace the viewer's animation with ``recording`` (which must show the same links)."""
        if [link_path(link) for link in recording.links] != [link_path(link) for link in self.links]:
            raise ValueError("the recording shows other links than the viewer draws")
        if len(recording.times) == 0:
            return
        self.show(recording.positions[0], recording.quaternions[0])
        fps = replay_frame_rate(recording.duration)
        self.meshcat.DeleteRecording()
        self.meshcat.StartRecording(fps, set_visualizations_while_recording=False)
        animation = self.meshcat.get_mutable_recording()
        frames = np.rint((recording.times - recording.times[0]) * fps).astype(int)
        for index, link in enumerate(recording.links):
            path = link_path(link)
            for f in _changing_frames(recording.positions[:, index], recording.quaternions[:, index]):
                animation.SetTransform(
                    int(frames[f]),
                    path,
                    _transform(recording.positions[f, index], recording.quaternions[f, index]),
                )
        self.meshcat.StopRecording()
        self.meshcat.PublishRecording()

    def static_html(self) -> str:
        """The scene and its animation as one self-contained page."""
        return str(self.meshcat.StaticHtml())


def _changing_frames(positions: FloatArray, quaternions: FloatArray) -> list[int]:
    """Frames to keep as key frames of one link: the first and last, and the ends of every
    run of frames in which it moves (linear interpolation between them is exact elsewhere)."""
    count = len(positions)
    if count <= 2:
        return list(range(count))
    pose = np.concatenate([positions, quaternions], axis=1)
    moved = np.any(np.abs(np.diff(pose, axis=0)) > _POSE_TOLERANCE, axis=1)
    keep = np.zeros(count, dtype=bool)
    keep[[0, -1]] = True
    keep[1:] |= moved
    keep[:-1] |= moved
    return [int(i) for i in np.flatnonzero(keep)]


def write_browser_replay(recording: SceneRecording, path: Path, camera: CameraView | None = None) -> Path:
    """Write ``recording`` as a self-contained page (atomically) and return its path."""
    viewer = SceneViewer(recording.links, camera)
    viewer.animate(recording)
    return write_atomically(path, viewer.static_html().encode())


def write_timeline_replay(
    kitchen: KitchenScene, timeline: Timeline, path: Path, live: LiveViewer | None = None
) -> Path:
    """``replay.html`` of the kinematic replay of ``timeline`` in ``kitchen`` (as built for the
    problem; left as it was), seen first from the GIF's camera; ``live`` gets the animation too."""
    recording = record_timeline(kitchen, timeline)
    if live is not None:
        live.play(recording)
    return write_browser_replay(recording, path, overview_camera(kitchen))


class LiveViewer:
    """The live viewer (``--meshcat``): the kitchen drawn in Meshcat, served on this machine while
    the program runs; ``update`` shows the kitchen as it is now, ``play`` gives it a recording."""

    def __init__(self, kitchen: KitchenScene) -> None:
        self._recorder = SceneRecorder(kitchen.scene)
        self._viewer = SceneViewer(self._recorder.links, overview_camera(kitchen), port=None)
        self.update()

    @property
    def url(self) -> str:
        """Where a browser on this machine sees the viewer."""
        return self._viewer.url

    def update(self) -> None:
        """Show every link where it is now (nothing, once the kitchen is closed)."""
        if self._recorder.scene.connected:
            self._viewer.show(*self._recorder.current_poses())

    def play(self, recording: SceneRecording) -> None:
        """Give the viewer ``recording`` as its animation (it plays when a browser is open)."""
        self._viewer.animate(recording)
