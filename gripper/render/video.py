"""Video of one scripted grasp trial: states recorded at the video rate, rendered afterwards.

During the trial a :class:`FrameRecorder` keeps the full physics state (and the cable tensions, or
the pneumatic gripper's chamber pressures)
whenever simulated time passes the next frame time; the states come from the rollout's own
per-step output, so recording costs no extra simulation. After the trial one
:class:`gripper.render.renderer.SceneRenderer` renders every kept state, an optional text overlay adds
phase, time and cable tensions, and ``mediapy`` writes H.264 MP4 (or GIF) through the
``imageio-ffmpeg`` binary. The file is written to a temporary name beside the target and moved
into place only when complete, so a failure leaves no half-written file.

Example:
    >>> from gripper.render.video import record_trial_video
    >>> info = record_trial_video("block", "block.mp4", seed=0)    # doctest: +SKIP
"""

from __future__ import annotations

import errno
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from gripper.core.atomic import check_output_file, write_atomic
from gripper.render.renderer import SceneRenderer, check_view

VIDEO_SUFFIXES = (".mp4", ".gif")


@dataclass
class FrameRecorder:
    """Keeps the trial's state every 1/fps seconds of simulated time."""

    fps: float = 30.0
    states: list = field(default_factory=list)
    phases: list = field(default_factory=list)
    tensions: list = field(default_factory=list)

    def start(self, model, probe) -> None:
        self.model = model
        # the drive's effort per finger (cable tension [N], chamber pressure [kPa], ...) in its display unit
        drive = probe.drive
        self.label, self.format = drive.effort_label, drive.effort_format
        self.tension_adr = probe.effort_adr
        self.scale = drive.effort_display_scale / probe.effort_divisor
        self._next = 0.0

    def add(self, phase: str, states: np.ndarray, sensordata: np.ndarray) -> None:
        for i, row in enumerate(states):  # row[0] is the time (mjSTATE_TIME comes first)
            if row[0] + 1e-9 >= self._next:
                self.states.append(row.copy())
                self.phases.append(phase)
                self.tensions.append(sensordata[i, self.tension_adr] * self.scale)
                self._next += 1.0 / self.fps


def check_output_path(out: str | Path, flag: str = "--out") -> Path:
    """The output path if a video can be written there, else ValueError naming ``flag``."""
    return check_output_file(out, flag, VIDEO_SUFFIXES)


class ProgressLines:
    """Progress of a loop over ``total`` items as lines for an ``on_progress`` callback.

    ``update(done)`` after each item says ``"rendering: 120/300 frames"`` once another tenth is
    done and at least ``min_interval_s`` has passed since the last line (so at most ten lines, and
    at most one a second); ``finish(done)`` says the last line.

    Example:
        >>> lines = []
        >>> p = ProgressLines(lines.append, 4, min_interval_s=0.0)
        >>> for i in range(1, 5):
        ...     p.update(i)
        >>> p.finish(4); lines[-1]
        'rendering: 4/4 frames'
    """

    def __init__(self, say: Callable[[str], None], total: int, *, what: str = "rendering", unit: str = "frames",
                 min_interval_s: float = 1.0):
        self.say, self.total, self.what, self.unit = say, max(int(total), 1), what, unit
        self.min_interval_s = min_interval_s
        self._step = max(self.total / 10.0, 1.0)
        self._next = self._step
        self._last_t = time.perf_counter()

    def update(self, done: int) -> None:
        now = time.perf_counter()
        if self._next <= done < self.total and now - self._last_t >= self.min_interval_s:
            self.say(f"{self.what}: {done}/{self.total} {self.unit}")
            self._last_t = now
            self._next = (done // self._step + 1) * self._step

    def finish(self, done: int, note: str = "") -> None:
        """The last line, ``done/done`` (``note`` says why, if the loop ended before ``total``)."""
        self.say(f"{self.what}: {done}/{done} {self.unit}{note}")


def overlay_band(height: int, n_lines: int = 2) -> int:
    """Height [px] of the black band :func:`overlay_lines` draws at the top of a frame."""
    return (max(10, height // 32) + 4) * n_lines + 6


def overlay_lines(frame: np.ndarray, lines: list[str]) -> np.ndarray:
    from PIL import Image, ImageDraw

    img = Image.fromarray(frame)
    draw = ImageDraw.Draw(img)
    h = max(10, frame.shape[0] // 32)
    draw.rectangle([0, 0, frame.shape[1], overlay_band(frame.shape[0], len(lines))], fill=(0, 0, 0))
    for k, text in enumerate(lines):
        draw.text((6, 4 + k * (h + 4)), text, fill=(255, 255, 255))
    return np.asarray(img)


def render_frames(rec: FrameRecorder, *, width: int = 640, height: int = 480, camera: str = "front",
                  overlay: bool = True, on_progress: Callable[[str], None] | None = None) -> np.ndarray:
    """Render every recorded state with one renderer; (n, height, width, 3) uint8.

    ``on_progress``: called with lines ``"rendering: 120/300 frames"`` (see :class:`ProgressLines`).
    """
    m = rec.model
    progress = ProgressLines(on_progress or (lambda msg: None), len(rec.states))
    renderer = SceneRenderer(m, width=width, height=height, camera=camera)
    d = mujoco.MjData(m)
    frames = np.empty((len(rec.states), height, width, 3), dtype=np.uint8)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    try:
        for i, s in enumerate(rec.states):
            mujoco.mj_setState(m, d, s, spec)
            mujoco.mj_forward(m, d)
            img = renderer.render(d)
            if overlay:
                tens = " ".join(format(t, rec.format) for t in rec.tensions[i])
                img = overlay_lines(img, [f"{rec.phases[i]:<8} t = {d.time:5.2f} s", f"{rec.label}: {tens}"])
            frames[i] = img
            progress.update(i + 1)
    finally:
        renderer.close()
    progress.finish(len(frames))
    return frames


def write_video(frames: np.ndarray, out: str | Path, fps: float) -> None:
    """Write ``frames`` to ``out`` (.mp4 H.264 or .gif) atomically."""
    import imageio_ffmpeg
    import mediapy

    out = check_output_path(out)
    mediapy.set_ffmpeg(imageio_ffmpeg.get_ffmpeg_exe())
    codec = "gif" if out.suffix.lower() == ".gif" else "h264"

    def encode(tmp: str) -> None:
        try:
            mediapy.write_video(tmp, frames, fps=fps, codec=codec)
        except RuntimeError as e:  # ffmpeg could not write (a full disk, a file size limit)
            detail = str(e).partition(": ")[2].strip() or "ffmpeg stopped writing: is the disk full?"
            raise OSError(errno.EIO, f"the video could not be written ({detail[:120]})", str(out)) from None
    write_atomic(out, encode)


def record_trial_video(obj, out: str | Path, *, seed: int = 0, index: int = 0, params=None, protocol=None,
                       noise=None, width: int = 640, height: int = 480, fps: float = 30.0,
                       camera: str = "front", overlay: bool = True, still: str | Path | None = None,
                       on_progress: Callable[[str], None] | None = None) -> dict:
    """Run one scripted trial and write its video; return the trial record plus video figures.

    ``still``: also write one frame as PNG, the first of the hold phase (the object lifted).
    ``on_progress``: called with a line as each stage starts (simulate, render, encode) and with
    ``"rendering: 120/300 frames"`` lines while rendering (each tenth, at most one a second).

    Raises:
        ValueError: bad output path, camera, size or fps (checked before the trial runs).
    """
    from gripper.experiments.trial import run_trial

    out = check_output_path(out)
    if still is not None:
        still = Path(still)
        if still.suffix.lower() != ".png" or not (still.parent if str(still.parent) else Path(".")).is_dir():
            raise ValueError(f"--still: must be a .png in an existing folder, got {still}")
    check_view(width, height, camera, prefix="--")
    if not (isinstance(fps, int | float) and 1 <= fps <= 120):
        raise ValueError(f"--fps: must be in [1, 120], got {fps!r}")
    say = on_progress or (lambda msg: None)
    rec = FrameRecorder(fps=float(fps))
    say(f"simulating the trial ({obj if isinstance(obj, str) else obj.name}, seed {seed}, trial {index}) ...")
    t0 = time.perf_counter()
    record = run_trial(obj, seed, index, params=params, protocol=protocol, noise=noise, frame_sink=rec)
    t_sim = time.perf_counter() - t0
    say(f"rendering {len(rec.states)} frames ({width}x{height}, camera {camera}) ...")
    t0 = time.perf_counter()
    frames = render_frames(rec, width=width, height=height, camera=camera, overlay=overlay, on_progress=say)
    t_render = time.perf_counter() - t0
    say(f"encoding {out.name} ...")
    t0 = time.perf_counter()
    write_video(frames, out, fps)
    t_write = time.perf_counter() - t0
    if still is not None:
        import mediapy

        k = rec.phases.index("hold") if "hold" in rec.phases else len(frames) // 2
        write_atomic(still, lambda tmp: mediapy.write_image(tmp, frames[k]))
    return {**record, "video": str(out), "frames": len(frames), "fps": fps, "width": width, "height": height,
            "simulate_s": t_sim, "render_s": t_render, "encode_s": t_write,
            "render_fps": len(frames) / t_render if t_render > 0 else float("inf")}
