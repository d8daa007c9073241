"""Offscreen video of a trial, the bending montage, the success plot, and bad input."""

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
from gripper.render.video import FrameRecorder, record_trial_video, render_frames

pytestmark = needs_gl

# A short trial: every phase present, 2.4 s of simulated time instead of 7.
SHORT = GraspProtocol(settle_s=0.1, close_hold_s=0.1, lift_height=0.02, lift_settle_s=0.05, hold_s=0.1,
                      shake_s=0.1, success_height=0.01)


def test_trial_video_reads_back_with_gripper_in_view(tmp_path):
    out = tmp_path / "trial.mp4"
    res = record_trial_video("block", out, seed=0, protocol=SHORT, width=160, height=120, fps=20)
    video = mediapy.read_video(str(out))
    n = len(video)
    assert video.shape[1:] == (120, 160, 3)
    assert video.metadata.fps == pytest.approx(20.0)
    # one frame per 1/fps of simulated time, the first at the first step
    assert abs(n - res["sim_time_s"] * 20) <= 1.0 and n == res["frames"]
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
