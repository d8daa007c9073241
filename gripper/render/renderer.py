"""Headless offscreen rendering of gripper scenes: camera presets and one reusable renderer.

The OpenGL backend is chosen when the first renderer is made
(:func:`gripper.render.backend.ensure_gl_backend`): ``MUJOCO_GL`` if the user set it, else
``egl`` (software Mesa EGL works with no display and no GPU), else ``osmesa`` where only that
library is installed.

Example:
    >>> from gripper.render.renderer import SceneRenderer                      # doctest: +SKIP
    >>> r = SceneRenderer(model, width=640, height=480, camera="front")  # doctest: +SKIP
    >>> rgb = r.render(data)                                           # doctest: +SKIP
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from gripper.render.backend import ensure_gl_backend, gl_error

# Presets. "palm" is the model's camera on the palm, looking down at the object; the others are
# free cameras set here (no change to the committed model): "front" and "side" look at the grasp
# from -y and +x, "top" straight down, "track" follows the palm body at a three-quarter view.
CAMERAS = ("front", "side", "top", "track", "palm")


# Software rendering (Mesa llvmpipe, no GPU) spends most of a frame on multisampling and the
# shadow map: without 4× MSAA and with a 1024 px shadow map (MuJoCo's defaults: 4×, 4096 px) a
# 640×480 frame renders about 3× faster here (4.2 -> 12.4 frames/s, measured side by side),
# with slightly harder edges and softer shadows.
SHADOW_SIZE = 1024


_MODEL_CAMERAS = {"palm": "palm_cam"}


@dataclass(frozen=True)
class FreeView:
    lookat: tuple[float, float, float]
    distance: float
    azimuth: float
    elevation: float


# "front" / "side": fixed, 0.5 m from a point 0.15 m above the grasp site, 15° down. They frame
# the whole trial: the gripper at its 0.25 m home height (settle, start of the approach), at the
# table (end of the approach) and lifted 0.10 m (hold, shake), with the object, below the text
# overlay's band at the top (at 320x240 the gripper spans rows 48-214 of 240; the scene's own
# "front" / "side" cameras, 0.2 m high, cut the lifted gripper off at the top edge).
# "top": straight down on the grasp site from 0.5 m; "track": 0.32 m from the palm's subtree
# centre of mass (the palm with its fingers), 12° down, from between two fingers, so the
# object inside the fingers stays visible under the palm.
_FREE = {"front": FreeView((0.0, 0.0, 0.15), 0.5, 90.0, -15.0),
         "side": FreeView((0.0, 0.0, 0.15), 0.5, 180.0, -15.0),
         "top": FreeView((0.0, 0.0, 0.05), 0.5, 90.0, -89.0),
         "track": FreeView((0.0, 0.0, 0.0), 0.32, 135.0, -12.0)}


def check_view(width, height, camera, *, prefix: str = "") -> None:
    """ValueError naming the argument (``prefix`` + name) for an unknown camera or an image size
    outside [16, 4096] pixels (the offscreen buffer is raised to the size, up to that bound)."""
    if camera not in CAMERAS:
        raise ValueError(f"{prefix}camera: unknown camera {camera!r}; allowed: {', '.join(CAMERAS)}")
    for name, v in (("width", width), ("height", height)):
        if not isinstance(v, int) or not 16 <= v <= 4096:
            raise ValueError(f"{prefix}{name}: must be an integer in [16, 4096] pixels, got {v!r}")


class SceneRenderer:
    """One ``mujoco.Renderer`` for a model, reused for every frame.

    Args:
        model: the compiled model.
        width, height: image size [px]; the model's offscreen buffer is enlarged if needed.
        camera: one of :data:`CAMERAS`.
        view: a free camera (lookat, distance, azimuth, elevation) used instead of ``camera``.
        antialias: 4× multisampling (MuJoCo's default); off by default, see :data:`SHADOW_SIZE`.
        shadow_size: shadow map size [px].

    The model's visual settings (offscreen buffer size, multisampling, shadow map) are set on
    ``model`` itself; they change pictures only, never the physics.

    Raises:
        ValueError: unknown camera or a bad size (one line naming the argument).
        RuntimeError: no OpenGL context could be started (says what to install).
    """

    def __init__(self, model, *, width: int = 640, height: int = 480, camera: str = "front",
                 view: FreeView | None = None, antialias: bool = False, shadow_size: int = SHADOW_SIZE):
        import mujoco

        check_view(width, height, camera)
        ensure_gl_backend()
        self.model = model
        # the offscreen framebuffer must hold the image: raise it for this model when needed
        model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
        model.vis.global_.offheight = max(model.vis.global_.offheight, height)
        model.vis.quality.offsamples = 4 if antialias else 0
        model.vis.quality.shadowsize = int(shadow_size)
        try:
            self._r = mujoco.Renderer(model, height=height, width=width)
        except Exception as e:  # the GL backends raise many types
            raise gl_error(e) from None
        self.camera = camera
        if view is None and camera in _MODEL_CAMERAS:
            self._cam = _MODEL_CAMERAS[camera]
        else:
            v = view or _FREE[camera]
            cam = mujoco.MjvCamera()
            cam.lookat[:] = v.lookat
            cam.distance, cam.azimuth, cam.elevation = v.distance, v.azimuth, v.elevation
            if camera == "track":
                cam.type = mujoco.mjtCamera.mjCAMERA_TRACKING
                cam.trackbodyid = model.body("palm").id
            else:
                cam.type = mujoco.mjtCamera.mjCAMERA_FREE
            self._cam = cam
        self.width, self.height = width, height

    def render(self, data, *, depth: bool = False, segmentation: bool = False):
        """RGB (h, w, 3) uint8, or depth (h, w) float32 [m], or segmentation (h, w, 2) int32
        (object id, object type) of ``data``'s current state."""
        r = self._r
        if depth:
            r.enable_depth_rendering()
        elif segmentation:
            r.enable_segmentation_rendering()
        try:
            r.update_scene(data, camera=self._cam)
            return r.render()
        finally:
            r.disable_depth_rendering()
            r.disable_segmentation_rendering()

    def close(self) -> None:
        self._r.close()


def open_viewer(model, data):
    """MuJoCo's passive viewer for ``render_mode="human"``; needs a display."""
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        raise RuntimeError("render_mode='human': no display (DISPLAY is not set); use 'rgb_array' "
                           "for headless rendering")
    import mujoco.viewer

    return mujoco.viewer.launch_passive(model, data)
