"""One clock for a whole run: increasing times, and playing it ends where the plan ends."""

from __future__ import annotations

import numpy as np
import pytest

from kitchen_tamp.execute import Verification, build_timeline, verify_trajectory
from kitchen_tamp.execute.render.replay_video import MIN_FRAMES, frame_times
from kitchen_tamp.kitchen import abstract_state, build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task


def test_times_increase_and_steps_start_in_order(refined: KitchenTrajectory, verified: Verification) -> None:
    timeline = build_timeline(refined, verified.tracks)
    times, qs = timeline.joint_samples()
    assert np.all(np.diff(times) >= 0.0) and len(qs) == len(times)
    assert np.all(np.diff(timeline.step_starts) > 0.0)
    assert timeline.actions == tuple(refined.plan)


@pytest.mark.slow
def test_playing_every_frame_ends_in_the_goal_state(
    kitchen_task: Task, refined: KitchenTrajectory, verified: Verification
) -> None:
    """Frames skip most replayed states, yet the boxes end where the judge left them."""
    timeline = build_timeline(refined, verified.tracks)
    times = frame_times(timeline)
    assert len(times) >= MIN_FRAMES
    with build_kitchen_for_task(kitchen_task) as kitchen:
        played = list(timeline.play(kitchen, times))
        assert len(played) == len(times)
        assert [step for _, step in played] == sorted(step for _, step in played)
        atoms = abstract_state(kitchen, kitchen_task.objects)
        played_poses = {name: body.base_pose() for name, body in kitchen.boxes.items()}
    with build_kitchen_for_task(kitchen_task) as judged:
        verify_trajectory(judged, kitchen_task, refined)
        for name, body in judged.boxes.items():
            assert max(played_poses[name].distance_to(body.base_pose())) < 1e-6, name
    assert kitchen_task.goal_atoms <= atoms
    assert np.allclose(timeline.segments[-1].segment.configurations[-1], refined.steps[-1].end)
