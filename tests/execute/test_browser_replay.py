"""replay.html: the recording follows the kinematic replay, the page is self-contained, and
in a real browser (headless Chromium) it loads without errors, draws the kitchen and animates
it for as long as the trajectory lasts."""

from __future__ import annotations

import re
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest

from kitchen_tamp.cli.final_project import main
from kitchen_tamp.execute import SavedRun, Verification, build_timeline, write_trajectory
from kitchen_tamp.execute.render.browser_replay import (
    HTML_FILE,
    MAX_FRAMES,
    MAX_FRAMES_PER_SECOND,
    _changing_frames,
    camera_eye,
    record_timeline,
    replay_frame_rate,
    write_timeline_replay,
)
from kitchen_tamp.execute.render.scene_recording import SceneRecorder, SceneRecording
from kitchen_tamp.execute.render.untextured_meshes import material_library_names, untextured_obj_text
from kitchen_tamp.kitchen import build_kitchen_for_task
from kitchen_tamp.kitchen.trajectory import KitchenTrajectory
from kitchen_tamp.planning import Task
from kitchen_tamp.world import CameraView, VisualKind, panda_urdf_path, visual_shapes

from .headless_chromium import HeadlessChromium, find_chromium

PROBLEM = Path(__file__).resolve().parents[2] / "pddl" / "problem.pddl"
PAGE_LOAD_TIMEOUT_S = 240.0
"""Generous: software WebGL on a busy two-core machine takes tens of seconds to parse the page."""


@pytest.fixture(scope="module")
def recording(kitchen_task: Task, refined: KitchenTrajectory, verified: Verification) -> SceneRecording:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        return record_timeline(kitchen, build_timeline(refined, verified.tracks))


@pytest.fixture(scope="module")
def page(
    kitchen_task: Task,
    refined: KitchenTrajectory,
    verified: Verification,
    tmp_path_factory: pytest.TempPathFactory,
) -> Path:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        path = tmp_path_factory.mktemp("page") / HTML_FILE
        return write_timeline_replay(kitchen, build_timeline(refined, verified.tracks), path)


def _index(recording: SceneRecording, body: str, link: str) -> int:
    return [(x.body, x.link) for x in recording.links].index((body, link))


@pytest.mark.slow
def test_recording_draws_every_visual_and_ends_where_the_replay_ends(
    kitchen_task: Task, refined: KitchenTrajectory, verified: Verification, recording: SceneRecording
) -> None:
    timeline = build_timeline(refined, verified.tracks)
    with build_kitchen_for_task(kitchen_task) as kitchen:
        before = kitchen.scene.save_state()
        again = record_timeline(kitchen, timeline)
        assert kitchen.scene.save_state() == before  # recording leaves the kitchen as it was
        for body in kitchen.scene.bodies:
            drawn = [v for link in recording.links if link.body == body.name for v in link.visuals]
            assert drawn and sorted(map(repr, drawn)) == sorted(map(repr, visual_shapes(body)))
        list(timeline.play(kitchen, np.array([timeline.duration])))
        for body in [kitchen.robot.body, *kitchen.boxes.values()]:
            for link in body.link_names:
                if any(x.body == body.name and x.link == link for x in recording.links):
                    index = _index(recording, body.name, link)
                    end = body.link_pose(link).position
                    assert np.allclose(recording.positions[-1, index], end, atol=1e-6)
    assert np.array_equal(again.positions, recording.positions)  # deterministic
    hand = [v for x in recording.links if x.link == "panda_hand" for v in x.visuals]
    assert hand and hand[0].kind is VisualKind.MESH and hand[0].mesh_path
    assert recording.times[0] == 0.0 and recording.times[-1] == pytest.approx(timeline.duration)
    assert len(recording.times) <= MAX_FRAMES
    assert np.min(np.diff(recording.times[:-1])) >= 1.0 / MAX_FRAMES_PER_SECOND - 1e-9  # not the last
    boxes = [i for i, x in enumerate(recording.links) if x.body in ("sugar", "spam")]
    assert len(boxes) == 2
    assert all(np.linalg.norm(recording.positions[-1, i] - recording.positions[0, i]) > 0.05 for i in boxes)


def test_recorder_refuses_frames_out_of_order(kitchen_task: Task) -> None:
    with build_kitchen_for_task(kitchen_task) as kitchen:
        recorder = SceneRecorder(kitchen.scene)
        recorder.capture(0.5)
        with pytest.raises(ValueError, match="not after"):
            recorder.capture(0.5)
        assert len(recorder.recording().times) == 1


def test_key_frames_reproduce_every_frame_by_linear_interpolation() -> None:
    rng = np.random.default_rng(0)
    positions = np.zeros((40, 3))
    positions[10:20] = np.cumsum(rng.normal(size=(10, 3)), axis=0)
    positions[20:30] = positions[19]
    positions[30:] = positions[19] + np.cumsum(rng.normal(size=(10, 3)), axis=0)
    quaternions = np.tile([0.0, 0.0, 0.0, 1.0], (40, 1))
    kept = _changing_frames(positions, quaternions)
    assert len(kept) < 40 and kept[0] == 0 and kept[-1] == 39
    frames = np.arange(40)
    for axis in range(3):
        assert np.allclose(np.interp(frames, kept, positions[kept, axis]), positions[:, axis])


def test_frame_rate_is_capped_so_long_runs_stay_small() -> None:
    assert replay_frame_rate(10.0) == MAX_FRAMES_PER_SECOND
    assert replay_frame_rate(600.0) * 600.0 <= MAX_FRAMES
    assert replay_frame_rate(1e6) == 1


def test_meshes_lose_only_their_texture_coordinates() -> None:
    text = (
        "# comment\nmtllib a.mtl\nmtllib gone.mtl\nv 1 2 3\nvt 0.5 0.5\nvn 0 0 1\n"
        "f 1/1/1 2/2/1 3/3/1\nf 1/1 2/2 3/3\n"
    )
    assert untextured_obj_text(text, frozenset({"a.mtl"})) == (
        "mtllib a.mtl\nv 1 2 3\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n"
    )
    panda_meshes = Path(panda_urdf_path()).parent / "meshes" / "visual"
    converted = untextured_obj_text((panda_meshes / "link6.obj").read_text(), frozenset({"link6.mtl"}))
    faces = [line for line in converted.splitlines() if line.startswith("f ")]
    assert faces and all(re.fullmatch(r"f( \d+(//\d+)?)+", face) for face in faces)
    assert not any(line.startswith("vt") for line in converted.splitlines())


def test_material_libraries_are_read_as_a_regular_expression_reads_them() -> None:
    every_line = re.compile(r"^mtllib[ \t]+(.*?)\s*$", re.MULTILINE)
    texts = [
        "mtllib first.mtl\nv 1 2 3\n  mtllib indented.mtl\nusemtl mtllib\nmtllib  spaced.mtl \r\nmtllib",
        "v 0 0 0\n# mtllib commented.mtl\nmtllib\tlast.mtl",
        "",
    ]
    panda_meshes = Path(panda_urdf_path()).parent / "meshes" / "visual"
    texts += [mesh.read_text(errors="replace") for mesh in sorted(panda_meshes.glob("*.obj"))]
    for text in texts:
        assert material_library_names(text) == every_line.findall(text)
    assert material_library_names(texts[0]) == ["first.mtl", "spaced.mtl"]


@pytest.mark.slow
def test_page_embeds_everything(page: Path) -> None:
    html = page.read_text()
    assert re.search(r"<script[^>]+src=", html) is None
    assert re.search(r"<link[^>]+href=", html) is None
    assert page.stat().st_size < 20e6


@pytest.mark.slow
def test_replay_page_loads_draws_the_kitchen_and_animates_the_whole_run_in_chromium(
    page: Path, recording: SceneRecording, tmp_path: Path
) -> None:
    executable, why = find_chromium()
    if executable is None:
        pytest.skip(f"cannot test replay.html in a browser: {why}")
    fps = replay_frame_rate(recording.duration)
    frame = len(recording.times) // 2
    seek = round(float(recording.times[frame]) * fps) / fps
    hand = _index(recording, "panda", "panda_hand")
    with HeadlessChromium(executable, width=800, height=500) as browser:
        browser.open(page.as_uri())
        loaded = "typeof viewer !== 'undefined' && viewer.animator.duration"
        duration = browser.wait_for(loaded, PAGE_LOAD_TIMEOUT_S)
        meshes = browser.evaluate(
            "(() => { let n = 0; viewer.scene.traverse(o => { n += o.isMesh ? 1 : 0; }); return n; })()"
        )
        slider_end = browser.evaluate("viewer.animator.time_scrubber.__max")
        browser.evaluate(f"viewer.animator.pause(), viewer.animator.seek({seek}), true")
        hand_position = browser.evaluate(
            "viewer.scene_tree.find(['kitchen_tamp', 'panda', 'panda_hand']).object.position.toArray()"
        )
        scene_shot = iio.imread(browser.screenshot())
        browser.evaluate("viewer.scene_tree.find(['kitchen_tamp']).object.visible = false, true")
        browser.evaluate("viewer.set_dirty(), true")
        empty_shot = iio.imread(browser.screenshot())
        errors, requests = browser.console_errors, browser.requests
    iio.imwrite(tmp_path / "replay_screenshot.png", scene_shot)
    assert errors == []
    assert all(url.startswith(("data:", "file:")) for url in requests), requests
    assert meshes >= sum(len(link.visuals) for link in recording.links)
    assert duration == pytest.approx(recording.duration, abs=1.0 / fps)
    assert slider_end == pytest.approx(duration)
    assert np.allclose(hand_position, recording.positions[frame, hand], atol=1e-4)
    colours = np.unique(scene_shot[..., :3].reshape(-1, 3), axis=0)
    changed = np.any(scene_shot[..., :3] != empty_shot[..., :3], axis=-1)
    assert len(colours) > 500  # shaded meshes and boxes, not a flat or blank canvas
    assert changed.mean() > 0.05  # the kitchen covers a good part of the picture


@pytest.mark.slow
def test_final_project_serves_the_live_viewer_without_waiting_for_anyone(
    refined: KitchenTrajectory, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    run = SavedRun(PROBLEM, PROBLEM.parent / "domain.pddl", "rrt", 0, refined)
    write_trajectory(tmp_path / "trajectory.json", run)
    assert main(["replay", str(tmp_path), "--meshcat", "--no-video"]) == 0
    assert re.search(r"live viewer \(Meshcat\) at http://\S+:\d+", capsys.readouterr().out)
    assert not (tmp_path / HTML_FILE).exists()  # --no-video: neither replay.gif nor replay.html


def test_page_camera_looks_along_the_gifs_line_of_sight() -> None:
    import pybullet as p

    view = CameraView(target=(0.4, -0.1, 0.6), distance=2.5, yaw=-60.0, pitch=-28.0)
    matrix = np.array(
        p.computeViewMatrixFromYawPitchRoll(view.target, view.distance, view.yaw, view.pitch, 0.0, 2)
    ).reshape(4, 4).T  # PyBullet's matrices are column-major
    gif_eye = -matrix[:3, :3].T @ matrix[:3, 3]
    target = np.asarray(view.target)
    gif_direction = (gif_eye - target) / np.linalg.norm(gif_eye - target)
    page_direction = (camera_eye(view) - target) / np.linalg.norm(camera_eye(view) - target)
    assert np.allclose(gif_direction, page_direction, atol=1e-6)


@pytest.mark.slow
def test_a_thinned_recording_keeps_its_ends_and_at_most_the_frames_asked_for(
    recording: SceneRecording,
) -> None:
    thinned = recording.thinned(10)
    assert 2 <= len(thinned.times) <= 10
    assert thinned.times[0] == recording.times[0] and thinned.times[-1] == recording.times[-1]
    assert np.array_equal(thinned.positions[-1], recording.positions[-1])
    assert recording.thinned(len(recording.times)) is recording
