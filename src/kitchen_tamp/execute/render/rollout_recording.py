"""A physics rollout recorded for ``replay.html``: `RolloutRecorder` is physics' frame callback,
`RecordedRollout` what it recorded. Apart from the page's writer (`browser_replay`), which loads
Drake: the process that runs physics records and never draws.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from kitchen_tamp.execute.render.scene_recording import SceneRecorder, SceneRecording
from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.kitchen.show import overview_camera
from kitchen_tamp.world import CameraView

if TYPE_CHECKING:  # the writer loads Drake
    from kitchen_tamp.execute.render.browser_replay import LiveViewer


@dataclass(frozen=True, eq=False)
class RecordedRollout:
    """What a `RolloutRecorder` recorded, without the scene it recorded (so that it can be sent
    from the process that ran physics to the one that writes the page)."""

    recording: SceneRecording
    camera: CameraView | None

    @property
    def captured(self) -> bool:
        """Whether at least two frames were recorded."""
        return len(self.recording.times) >= 2

    def write(self, path: Path, live: LiveViewer | None = None) -> Path:
        """``replay.html`` of what was recorded (thinned to ``MAX_FRAMES``); ``live`` gets it too."""
        from kitchen_tamp.execute.render.browser_replay import MAX_FRAMES, write_browser_replay

        recording = self.recording.thinned(MAX_FRAMES)
        if live is not None:
            live.play(recording)
        return write_browser_replay(recording, path, self.camera)


class RolloutRecorder:
    """An ``on_frame(time_s, kitchen)`` callback for a physics rollout: records the kitchen it is
    shown (the simulator's own), so that ``replay.html`` shows the physical motion."""

    def __init__(self) -> None:
        self._recorder: SceneRecorder | None = None
        self._camera: CameraView | None = None

    def __call__(self, time_s: float, kitchen: KitchenScene) -> None:
        if self._recorder is None:
            self._recorder = SceneRecorder(kitchen.scene)
            self._camera = overview_camera(kitchen)
        self._recorder.capture(time_s)

    def recorded(self) -> RecordedRollout | None:
        """What was recorded (None before the first frame)."""
        if self._recorder is None:
            return None
        return RecordedRollout(self._recorder.recording(), self._camera)

    @property
    def captured(self) -> bool:
        """Whether at least two frames were recorded."""
        recorded = self.recorded()
        return recorded is not None and recorded.captured

    def write(self, path: Path, live: LiveViewer | None = None) -> Path:
        """``replay.html`` of what was recorded (thinned to ``MAX_FRAMES``); ``live`` gets it too."""
        recorded = self.recorded()
        if recorded is None:
            raise ValueError("no frame of the rollout was recorded")
        return recorded.write(path, live)
