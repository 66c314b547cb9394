"""Frames of a scene for viewers: every visible link's world pose at given times.

A ``SceneRecorder`` reads a PyBullet ``Scene`` as it is whenever ``capture`` is
called, so it does not care what moved the scene: the kinematic replay of a
trajectory, or a physics rollout stepping the simulation. The ``SceneRecording``
it returns is plain data (link names, their visuals, times, poses) that a viewer
draws without PyBullet.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kitchen_tamp.world import Body, FloatArray, Scene, VisualShape, visual_shapes


@dataclass(frozen=True)
class RecordedLink:
    """A link that has something to draw: its body, its name and its visuals."""

    body: str
    link: str
    visuals: tuple[VisualShape, ...]


@dataclass(frozen=True, eq=False)
class SceneRecording:
    """``positions[f, i]`` and ``quaternions[f, i]`` (x, y, z, w) are the world pose of
    ``links[i]``'s URDF frame at ``times[f]`` (seconds, increasing)."""

    links: tuple[RecordedLink, ...]
    times: FloatArray
    positions: FloatArray
    quaternions: FloatArray

    def __post_init__(self) -> None:
        frames, count = len(self.times), len(self.links)
        if self.positions.shape != (frames, count, 3) or self.quaternions.shape != (frames, count, 4):
            raise ValueError(
                f"a recording of {frames} frames of {count} links needs positions ({frames}, {count}, 3) "
                f"and quaternions ({frames}, {count}, 4), got {self.positions.shape} and "
                f"{self.quaternions.shape}"
            )
        if np.any(np.diff(self.times) <= 0.0):
            raise ValueError("recording times must increase")

    def thinned(self, max_frames: int) -> SceneRecording:
        """Every k-th frame (the last always kept), so that at most ``max_frames`` remain."""
        if max_frames < 2:
            raise ValueError(f"a thinned recording keeps at least 2 frames, not {max_frames}")
        if len(self.times) <= max_frames:
            return self
        stride = int(np.ceil((len(self.times) - 1) / (max_frames - 1)))
        keep = np.append(np.arange(0, len(self.times) - 1, stride), len(self.times) - 1)
        return SceneRecording(self.links, self.times[keep], self.positions[keep], self.quaternions[keep])

    @property
    def duration(self) -> float:
        """Seconds from the first frame to the last."""
        return float(self.times[-1] - self.times[0]) if len(self.times) else 0.0


class SceneRecorder:
    """Captures the world pose of every link of ``scene`` that has a visual, frame by frame."""

    def __init__(self, scene: Scene) -> None:
        scene.require_visuals("recording a scene for a viewer")
        self.scene = scene
        links: list[RecordedLink] = []
        self._sources: list[tuple[Body, tuple[str, ...]]] = []
        for body in scene.bodies:
            shapes = visual_shapes(body)
            drawn = tuple(link for link in body.link_names if any(s.link == link for s in shapes))
            links.extend(
                RecordedLink(body.name, link, tuple(s for s in shapes if s.link == link)) for link in drawn
            )
            if drawn:
                self._sources.append((body, drawn))
        self.links = tuple(links)
        self._times: list[float] = []
        self._positions: list[FloatArray] = []
        self._quaternions: list[FloatArray] = []

    def current_poses(self) -> tuple[FloatArray, FloatArray]:
        """World positions (links, 3) and quaternions (links, 4) of every link now."""
        frames = [body.link_frames(links) for body, links in self._sources]
        positions = np.concatenate([positions for positions, _ in frames]).reshape(-1, 3)
        quaternions = np.concatenate([quaternions for _, quaternions in frames]).reshape(-1, 4)
        return positions, quaternions

    def capture(self, time_s: float) -> None:
        """Record every link's pose now, as the frame at ``time_s`` (later than the last)."""
        if self._times and time_s <= self._times[-1]:
            raise ValueError(f"frame at {time_s} s is not after the last one at {self._times[-1]} s")
        positions, quaternions = self.current_poses()
        self._times.append(float(time_s))
        self._positions.append(positions)
        self._quaternions.append(quaternions)

    def recording(self) -> SceneRecording:
        """The frames captured so far."""
        count = len(self.links)
        return SceneRecording(
            self.links,
            np.array(self._times, dtype=float),
            np.array(self._positions, dtype=float).reshape(len(self._times), count, 3),
            np.array(self._quaternions, dtype=float).reshape(len(self._times), count, 4),
        )
