"""replay.gif: lighter robot meshes draw the same picture, the still background and the moving
layer (drawn only where something moving can show) put together are the picture a full drawing
gives (but for a pixel on an edge now and then), one shared palette keeps the frames
faithful, and the pictures drawn in a second process arrive (or say why not)."""

from __future__ import annotations

import time
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest

from kitchen_tamp.execute import Timeline, build_timeline, verify_trajectory
from kitchen_tamp.execute.render.background_pictures import PendingPictures, PictureError, PictureJob
from kitchen_tamp.execute.render.low_poly_meshes import cluster_obj_text
from kitchen_tamp.execute.render.replay_video import (
    LayeredFrames,
    frame_times,
    low_poly_robot,
    write_gif,
)
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.scene.choice import choose_scene
from kitchen_tamp.kitchen.show import overview_camera
from kitchen_tamp.planning import Task
from kitchen_tamp.world import CameraView, PixelWindow, Scene, panda_urdf_path, render, render_with_depth
from tests.conftest import KitchenRuns

GRID_OBJ = "\n".join(
    ["mtllib grid.mtl", "usemtl white"]
    + [f"v {x * 0.001} {y * 0.001} 0" for x in range(20) for y in range(20)]
    + ["vt 0.5 0.5", "vn 0 0 1"]
    + [f"f {a}/1/1 {a + 1}/1/1 {a + 20}/1/1"
       for x in range(19) for y in range(19) if (a := x * 20 + y + 1)]
) + "\n"
"""A 19 mm square plate of 361 triangles, one vertex a millimetre."""


def test_clustering_merges_vertices_and_keeps_everything_else() -> None:
    clustered = cluster_obj_text(GRID_OBJ, cluster_size=0.005)
    lines = clustered.splitlines()
    vertices = np.array([[float(v) for v in line.split()[1:]] for line in lines if line.startswith("v ")])
    faces = [line for line in lines if line.startswith("f ")]
    assert len(vertices) == 16 and 0 < len(faces) < 361
    assert np.all(vertices >= 0.0) and np.all(vertices <= 0.019)  # means of cells of the plate
    assert all(corner.endswith("/1/1") for face in faces for corner in face.split()[1:])
    assert [line for line in lines if not line.startswith(("v ", "f "))] == [
        "mtllib grid.mtl", "usemtl white", "vt 0.5 0.5", "vn 0 0 1"]
    assert len({tuple(sorted(face.split()[1:])) for face in faces}) == len(faces)  # none repeated


@pytest.fixture(scope="module")
def problem_timeline(kitchen_runs: KitchenRuns) -> tuple[Task, Timeline]:
    planned = kitchen_runs.refined("problem.pddl", "rrt", 0)
    with build_kitchen_for_task(planned.task) as kitchen:
        verification = verify_trajectory(kitchen, planned.task, planned.trajectory)
    return planned.task, build_timeline(planned.trajectory, verification.tracks)


@pytest.mark.slow
def test_layered_frames_are_full_drawings_and_stand_ins_look_alike(
    problem_timeline: tuple[Task, Timeline],
) -> None:
    task, timeline = problem_timeline
    times = frame_times(timeline)[::30]
    with build_kitchen_for_task(task) as kitchen:
        view = overview_camera(kitchen, 400, 300)
        originals = [render(kitchen.scene, view) for _ in timeline.play(kitchen, times)]
        stand_ins = low_poly_robot(kitchen)
        layers = LayeredFrames(kitchen, stand_ins, view)
        layered = []
        for _ in timeline.play(kitchen, times):
            stand_ins.follow()
            layered.append(layers.frame())
        layers.close()
        full = []
        for _ in timeline.play(kitchen, times):
            stand_ins.follow()
            full.append(render(kitchen.scene, view))
    for original, whole, parts in zip(originals, full, layered, strict=True):
        assert (np.abs(parts.astype(int) - whole.astype(int)).max(axis=2) > 8).mean() < 5e-4  # edge pixels
        differing = np.abs(original.astype(int) - whole.astype(int)).max(axis=2) > 40
        assert differing.mean() < 0.01  # the lighter meshes change under 1% of the pixels
    assert not np.array_equal(layered[0], layered[-1])  # the arm moved


def test_gif_frames_keep_their_colours(tmp_path: Path) -> None:
    shades = np.linspace(0, 255, 60).astype(np.uint8)
    background = np.stack([np.tile(shades[:, None], (1, 80))] * 3, axis=2)  # a grey ramp
    frames = []
    for k in range(12):  # a blue box moving across, an orange bar from the sixth frame on
        frame = background.copy()
        frame[10:30, 5 + 5 * k : 25 + 5 * k] = (40, 90, 200)
        if k >= 6:
            frame[40:55, 10:70] = (230, 120, 20)
        frames.append(frame)
    path = write_gif(tmp_path / "replay.gif", frames, 0.1)
    decoded = iio.imread(path, index=None)[..., :3].astype(int)
    assert decoded.shape == (12, 60, 80, 3)
    assert np.abs(decoded - np.array(frames).astype(int)).max() <= 8


@pytest.mark.slow
def test_pictures_drawn_beside_the_run_arrive(
    problem_timeline: tuple[Task, Timeline], tmp_path: Path
) -> None:
    task, timeline = problem_timeline
    job = PictureJob(task, choose_scene("problem.pddl").kitchen_map(), timeline, tmp_path, "joints")
    pictures = PendingPictures(job).result()
    assert pictures.gif == tmp_path / "replay.gif" and pictures.frames == len(frame_times(timeline))
    stored = len(iio.imread(pictures.gif, index=None))
    assert 0.9 * pictures.frames <= stored <= pictures.frames  # repeated frames are merged
    assert pictures.joints is not None and pictures.joints.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_pictures_started_before_the_timeline_is_known_draw_it_once_handed_over(
    problem_timeline: tuple[Task, Timeline], tmp_path: Path
) -> None:
    task, timeline = problem_timeline
    kitchen_map = choose_scene("problem.pddl").kitchen_map()
    pending = PendingPictures(PictureJob(task, kitchen_map, None, tmp_path, "joints", gif=False))
    time.sleep(0.5)  # the child gets ready meanwhile, as while the judge reads the plan
    pending.draw(timeline)
    pictures = pending.result()
    assert pictures.joints == tmp_path / "joints.png" and pictures.gif is None
    gif_job = PictureJob(task, kitchen_map, None, tmp_path / "gif", "joints", joints=False)
    (tmp_path / "gif").mkdir()
    pending = PendingPictures(gif_job)
    time.sleep(0.5)  # the camera, the stand-ins and the background are made meanwhile
    pending.draw(timeline)
    drawn = pending.result()
    assert drawn.frames == len(frame_times(timeline))
    (tmp_path / "at-once").mkdir()
    at_once = PendingPictures(PictureJob(task, kitchen_map, timeline, tmp_path / "at-once", "joints",
                                         joints=False)).result()
    assert drawn.gif is not None and at_once.gif is not None
    assert drawn.gif.read_bytes() == at_once.gif.read_bytes()


@pytest.mark.slow
def test_a_failure_in_the_drawing_process_comes_back_with_its_traceback(
    problem_timeline: tuple[Task, Timeline], tmp_path: Path
) -> None:
    task, timeline = problem_timeline
    blocked = tmp_path / "a file"
    blocked.write_text("not a folder")
    kitchen_map = choose_scene("problem.pddl").kitchen_map()
    job = PictureJob(task, kitchen_map, timeline, blocked, "joints", gif=False)
    with pytest.raises(PictureError, match="Traceback"):
        PendingPictures(job).result()


def test_a_window_of_the_picture_is_drawn_as_the_whole_picture_draws_it() -> None:
    with Scene() as scene:
        scene.load_urdf("panda", panda_urdf_path(), fixed_base=True)
        view = CameraView((0.0, 0.0, 0.5), 1.6, yaw=40.0, pitch=-25.0, width=160, height=120)
        whole, whole_depth = render_with_depth(scene, view)
        window = PixelWindow(top=20, bottom=90, left=50, right=130)
        part, part_depth = render_with_depth(scene, view, window)
    assert part.shape == (70, 80, 3)
    differing = np.abs(part.astype(int) - whole[20:90, 50:130].astype(int)).max(axis=2) > 8
    assert differing.mean() < 0.002 and np.allclose(part_depth, whole_depth[20:90, 50:130], atol=1e-4)
    assert (part_depth < 1.0).mean() > 0.1  # the robot is in the window


@pytest.mark.slow
def test_cancelled_pictures_leave_nothing_behind(
    problem_timeline: tuple[Task, Timeline], tmp_path: Path
) -> None:
    task, timeline = problem_timeline
    kitchen_map = choose_scene("problem.pddl").kitchen_map()
    job = PictureJob(task, kitchen_map, timeline, tmp_path, "joints", joints=False)
    pending = PendingPictures(job)
    time.sleep(0.5)  # drawing by now
    pending.cancel()
    assert not list(tmp_path.glob(".*.tmp"))  # nothing half-written
    if (tmp_path / "replay.gif").exists():  # a fast machine finished it
        assert len(iio.imread(tmp_path / "replay.gif", index=None)) > 1
