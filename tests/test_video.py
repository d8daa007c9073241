"""Offscreen video of a trial, the bending montage, the success plot, and bad input."""

import math
import os
import subprocess
import sys

import imageio_ffmpeg
import mediapy
import mujoco
import numpy as np
import pytest
from conftest import needs_gl

from gripper.experiments.protocol import GraspProtocol
from gripper.render.video import FrameRecorder, ProgressLines, overlay_band, record_trial_video, render_frames

pytestmark = needs_gl

# A short trial: every phase present, 2.4 s of simulated time instead of 7.
SHORT = GraspProtocol(settle_s=0.1, close_hold_s=0.1, lift_height=0.02, lift_settle_s=0.05, hold_s=0.1,
                      shake_s=0.1, success_height=0.01)


def test_trial_video_reads_back_with_gripper_in_view(tmp_path):
    out = tmp_path / "trial.mp4"
    lines = []
    res = record_trial_video("block", out, seed=0, protocol=SHORT, width=160, height=120, fps=20,
                             on_progress=lines.append)
    # stage lines, then progress while rendering: "rendering: k/n frames", the last one n/n
    n_frames = res["frames"]
    counts = [line for line in lines if line.startswith("rendering: ")]
    assert counts[-1] == f"rendering: {n_frames}/{n_frames} frames", lines
    assert len(counts) <= 10 and lines[-1].startswith("encoding trial.mp4"), lines
    video = mediapy.read_video(str(out))
    n = len(video)
    assert video.shape[1:] == (120, 160, 3)
    assert video.metadata.fps == pytest.approx(20.0)
    # one frame per 1/fps of simulated time, the first at the first step: n = floor(T fps) + 1
    assert n == math.floor(res["sim_time_s"] * 20 + 1e-9) + 1 and n == res["frames"]
    assert min(f.astype(float).var() for f in video) > 20.0  # no blank frame
    assert np.abs(video[-1].astype(float) - video[0].astype(float)).mean() > 1.0  # the scene moves


def test_gripper_is_in_view_of_every_camera_preset():
    rec = FrameRecorder(fps=5)
    from gripper.experiments.trial import run_trial
    run_trial("block", 0, 0, protocol=SHORT, frame_sink=rec)
    m = rec.model
    gripper_geoms = {g for g in range(m.ngeom)
                     if m.body(m.geom_bodyid[g]).name == "palm" or m.body(m.geom_bodyid[g]).name.startswith("f")}
    from gripper.render.renderer import CAMERAS, SceneRenderer
    d = mujoco.MjData(m)
    mujoco.mj_setState(m, d, rec.states[len(rec.states) // 2], mujoco.mjtState.mjSTATE_FULLPHYSICS)
    mujoco.mj_forward(m, d)
    for cam in CAMERAS:
        r = SceneRenderer(m, width=160, height=120, camera=cam)
        seg = r.render(d, segmentation=True)
        r.close()
        ids, types = seg[..., 0], seg[..., 1]
        is_gripper = (types == int(mujoco.mjtObj.mjOBJ_GEOM)) & np.isin(ids, list(gripper_geoms))
        assert is_gripper.mean() > 0.005, cam  # at least 0.5 % of the pixels show the gripper


def test_progress_lines_each_tenth_at_most_once_a_second():
    lines = []
    p = ProgressLines(lines.append, 300, min_interval_s=0.0)
    for i in range(1, 301):
        p.update(i)
    p.finish(300)
    assert lines == [f"rendering: {k}/300 frames" for k in range(30, 301, 30)]
    lines.clear()
    p = ProgressLines(lines.append, 300, min_interval_s=3600.0)  # a fast loop: only the last line
    for i in range(1, 301):
        p.update(i)
    p.finish(300)
    assert lines == ["rendering: 300/300 frames"]


def _synthetic_frames(n=7, h=48, w=64):
    y, x = np.mgrid[0:h, 0:w]
    return np.stack([np.stack([(x * 4 + 20 * k) % 256, (y * 5) % 256, np.full_like(x, 40 * k % 256)], -1)
                     for k in range(n)]).astype(np.uint8)


def test_own_mp4_reads_back_with_mediapy(tmp_path):
    """The package's writer (H.264 through imageio-ffmpeg) and mediapy.read_video agree."""
    from gripper.render.video import write_video
    frames = _synthetic_frames()
    out = tmp_path / "own.mp4"
    write_video(frames, out, fps=10)
    video = mediapy.read_video(str(out))
    assert video.shape == frames.shape
    assert np.abs(video.astype(float) - frames.astype(float)).mean() < 20.0  # lossy, but the same picture


def test_import_gripper_lets_mediapy_read_video_without_system_ffmpeg(tmp_path):
    """A fresh interpreter with no ffmpeg on PATH: ``import gripper`` (which imports no mediapy)
    makes mediapy find imageio-ffmpeg's binary, in either import order."""
    from gripper.render.video import write_video
    out = tmp_path / "own.mp4"
    write_video(_synthetic_frames(n=5), out, fps=10)
    env = {**os.environ, "PATH": str(tmp_path / "empty")}  # no ffmpeg on it (not even the venv's link)
    for code in ("import sys, gripper; assert 'mediapy' not in sys.modules and 'imageio_ffmpeg' not in sys.modules; "
                 "import mediapy; print(len(mediapy.read_video(sys.argv[1])))",
                 "import sys, mediapy, gripper; print(len(mediapy.read_video(sys.argv[1])))"):
        res = subprocess.run([sys.executable, "-c", code, str(out)], capture_output=True, text=True, env=env,
                             timeout=120)
        assert res.returncode == 0 and res.stdout.strip() == "5", res.stdout + res.stderr


def test_the_activated_environment_reads_video_with_mediapy_alone(tmp_path):
    """The project's environment as `source .venv/bin/activate` leaves it (its bin/ on PATH):
    mediapy alone, with no gripper import, reads the tool's MP4 through the ffmpeg link that
    scripts/setup.sh puts there."""
    from gripper.render.video import write_video
    out = tmp_path / "own.mp4"
    write_video(_synthetic_frames(n=5), out, fps=10)
    env = {**os.environ, "PATH": os.path.dirname(sys.executable)}
    code = "import sys, mediapy; print(len(mediapy.read_video(sys.argv[1])))"
    res = subprocess.run([sys.executable, "-c", code, str(out)], capture_output=True, text=True, env=env, timeout=120)
    assert res.returncode == 0 and res.stdout.strip() == "5", res.stdout + res.stderr


def test_the_environment_reads_video_with_mediapy_alone_without_activation(tmp_path):
    """`.venv/bin/python -c "import mediapy; mediapy.read_video(...)"` with the environment not
    activated (its bin/ not on PATH): the interpreter puts its bin/ there at start-up
    (scripts/setup.sh's .pth line), so mediapy finds the ffmpeg link."""
    from gripper.render.video import write_video
    out = tmp_path / "own.mp4"
    write_video(_synthetic_frames(n=5), out, fps=10)
    env = {**os.environ, "PATH": "/usr/bin:/bin"}
    code = "import sys, mediapy; print(len(mediapy.read_video(sys.argv[1])))"
    res = subprocess.run([sys.executable, "-c", code, str(out)], capture_output=True, text=True, env=env, timeout=120)
    assert res.returncode == 0 and res.stdout.strip() == "5", res.stdout + res.stderr


def test_fixed_cameras_frame_the_gripper_from_home_to_hold():
    """"front" and "side" show the whole gripper below the overlay band and inside the picture:
    at its home height (first frame), at the end of the approach and lifted (first hold frame)."""
    from gripper.experiments.trial import run_trial
    from gripper.render.renderer import SceneRenderer
    rec = FrameRecorder(fps=10)
    run_trial("block", 0, 0, protocol=GraspProtocol(hold_s=0.1, shake_s=0.1), frame_sink=rec)  # 0.10 m lift
    m = rec.model
    gripper_geoms = [g for g in range(m.ngeom)
                     if m.body(m.geom_bodyid[g]).name == "palm" or m.body(m.geom_bodyid[g]).name.startswith("f")]
    last_approach = len(rec.phases) - 1 - rec.phases[::-1].index("approach")
    frames = {"home": 0, "approach": last_approach, "hold": rec.phases.index("hold")}
    width, height = 320, 240
    top, margin = overlay_band(height), 4
    d = mujoco.MjData(m)
    for cam in ("front", "side"):
        r = SceneRenderer(m, width=width, height=height, camera=cam)
        try:
            for when, k in frames.items():
                mujoco.mj_setState(m, d, rec.states[k], mujoco.mjtState.mjSTATE_FULLPHYSICS)
                mujoco.mj_forward(m, d)
                seg = r.render(d, segmentation=True)
                mask = (seg[..., 1] == int(mujoco.mjtObj.mjOBJ_GEOM)) & np.isin(seg[..., 0], gripper_geoms)
                rows, cols = np.nonzero(mask)
                assert len(rows) > 0.01 * width * height, (cam, when)
                assert rows.min() >= top + margin and rows.max() < height - margin, (cam, when, rows.min(), rows.max())
                assert cols.min() >= margin and cols.max() < width - margin, (cam, when, cols.min(), cols.max())
        finally:
            r.close()


def test_policy_video_reports_progress(tmp_path):
    from gripper.rl.policy_video import record_policy_video
    lines = []
    res = record_policy_video(lambda obs: np.zeros((len(obs), 5), dtype=np.float32),
                              {"objects": "block", "max_episode_steps": 12}, tmp_path / "p.mp4", seed=0,
                              width=64, height=48, on_progress=lines.append)
    assert res["frames"] == 13 and lines[-1] == "encoding p.mp4 ...", lines
    assert lines[-2] == "rendering: 13/13 frames", lines
    assert len(mediapy.read_video(str(tmp_path / "p.mp4"))) == 13


def test_gif_output_and_overlay(tmp_path):
    rec = FrameRecorder(fps=5)
    from gripper.experiments.trial import run_trial
    run_trial("block", 0, 0, protocol=SHORT, frame_sink=rec)
    plain = render_frames(rec, width=160, height=120, overlay=False)
    text = render_frames(rec, width=160, height=120, overlay=True)
    assert (plain[:, :8] != text[:, :8]).any()  # the overlay band is drawn at the top
    from gripper.render.video import write_video
    write_video(plain, tmp_path / "t.gif", fps=5)
    assert len(mediapy.read_video(str(tmp_path / "t.gif"))) == len(plain)


def test_bending_montage(tmp_path):
    from gripper.experiments.bending import BendingConfig
    from gripper.render.figures import bending_figure
    out = tmp_path / "bend.png"
    bending_figure(out, BendingConfig(duration=0.5, n_points=31))
    img = mediapy.read_image(str(out))
    assert img.shape[:2] == (640, 1200)
    assert img[..., :3].astype(float).var() > 100.0


def test_success_plot(tmp_path):
    from gripper.render.figures import success_plot
    summary = {"objects": {"block": {"success_rate": 0.9, "ci95": [0.6, 0.98], "trials": 10},
                           "balloon": {"success_rate": 1.0, "ci95": [0.72, 0.9999999999999999], "trials": 10}}}
    success_plot(summary, tmp_path / "s.png")
    assert mediapy.read_image(str(tmp_path / "s.png")).shape[0] > 100


def _cli(*args):
    env = {**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")}
    return subprocess.run([sys.executable, "-m", "gripper.cli.main", "video", *args], capture_output=True, text=True,
                          env=env, timeout=300)


@pytest.mark.parametrize("extra, field", [
    (["--out", "/nonexistent_dir/x.mp4"], "--out"),
    (["--out", "{tmp}/x.avi"], "--out"),
    (["--out", "{tmp}/x.mp4", "--camera", "drone"], "--camera"),
    (["--out", "{tmp}/x.mp4", "--width", "9000"], "--width"),
    (["--out", "{tmp}/x.mp4", "--object", "teapot"], "unknown object"),
])
def test_video_bad_input_exit_2_and_no_file(tmp_path, extra, field):
    args = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    if "--object" not in args:
        args += ["--object", "block"]
    res = _cli(*args)
    assert res.returncode == 2, res.stderr
    assert field in res.stderr and len(res.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_unwritable_folder(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        if os.access(ro, os.W_OK):  # running as root: permissions are not enforced
            pytest.skip("permissions not enforced for this user")
        res = _cli("--object", "block", "--out", str(ro / "x.mp4"))
        assert res.returncode == 2 and "not writable" in res.stderr
        assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o700)


def test_ffmpeg_is_the_bundled_one():
    assert os.path.isfile(imageio_ffmpeg.get_ffmpeg_exe())
