"""The OpenGL backend for headless rendering, chosen when something first renders.

MuJoCo binds its OpenGL backend (``MUJOCO_GL``) when ``mujoco`` is imported, and with ``egl``
that import maps Mesa's EGL and GL libraries into the process. Some libraries loaded later
crash next to them (PyTorch's optimisers, through triton's native module), so importing
``gripper`` and simulating must not touch a graphics library:

- :func:`defer_gl_backend` (run by ``import gripper``): if the user did not set ``MUJOCO_GL``,
  set it to ``disable`` and mark the choice as deferred (``GRIPPER_GL_DEFERRED``, inherited by
  worker processes). MuJoCo then loads no OpenGL backend at all.
- :func:`ensure_gl_backend` (run before the first render): if the choice was deferred, probe
  in a child process whether an EGL display starts; use ``egl`` if so, else ``osmesa`` if
  libOSMesa is installed; point MuJoCo's renderer at that backend. A ``MUJOCO_GL`` the user
  set is always kept.

The video encoder: the package writes and reads video with ``mediapy``, which runs an ``ffmpeg``
program and by default looks for one on ``PATH``; the project installs its own binary with the
``imageio-ffmpeg`` wheel instead. :func:`use_bundled_ffmpeg` (run when this module is imported,
that is by ``import gripper``) points ``mediapy`` at that binary if ``mediapy`` finds no
``ffmpeg`` of its own, so ``mediapy.read_video`` reads the tool's MP4 files on a machine with
no system ffmpeg. ``mediapy`` takes about 0.8 s to import (matplotlib), so it is not imported
here: if it is not imported yet, it is set up right after its first import
(:func:`gripper.core.after_import.after_import`).
"""

from __future__ import annotations

import ctypes.util
import importlib
import os
import subprocess
import sys

from gripper.core.after_import import after_import

DEFERRED = "GRIPPER_GL_DEFERRED"

# Run in a child process: exit 0 if a headless EGL display can be initialised, the way MuJoCo's
# EGL backend opens one (an EGL device via eglQueryDevicesEXT / eglGetPlatformDisplayEXT).
_EGL_PROBE = """
import ctypes, ctypes.util, sys
name = ctypes.util.find_library("EGL")
if not name:
    sys.exit(1)
lib = ctypes.CDLL(name)
lib.eglGetProcAddress.restype = ctypes.c_void_p
lib.eglGetProcAddress.argtypes = [ctypes.c_char_p]
lib.eglInitialize.restype = ctypes.c_uint
lib.eglInitialize.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
lib.eglTerminate.argtypes = [ctypes.c_void_p]
q = lib.eglGetProcAddress(b"eglQueryDevicesEXT")
g = lib.eglGetProcAddress(b"eglGetPlatformDisplayEXT")
if not (q and g):
    sys.exit(1)
query = ctypes.CFUNCTYPE(ctypes.c_uint, ctypes.c_int, ctypes.POINTER(ctypes.c_void_p),
                         ctypes.POINTER(ctypes.c_int))(q)
get_display = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_void_p)(g)
devices = (ctypes.c_void_p * 16)()
n = ctypes.c_int(0)
if not query(16, devices, ctypes.byref(n)):
    sys.exit(1)
for i in range(n.value):
    dpy = get_display(0x313F, devices[i], None)  # EGL_PLATFORM_DEVICE_EXT
    if dpy and lib.eglInitialize(dpy, None, None):
        lib.eglTerminate(dpy)
        sys.exit(0)
sys.exit(1)
"""
# The probe is a ctypes call into Mesa; it takes about 0.1 s and cannot hang on a headless
# machine, but a broken driver stack must not stall the first render for long.
PROBE_TIMEOUT_S = 20.0


def defer_gl_backend() -> None:
    """Keep MuJoCo from loading an OpenGL backend until something renders (see the module
    docstring); a ``MUJOCO_GL`` the user set is kept."""
    if not os.environ.get("MUJOCO_GL"):  # unset or empty: MuJoCo's default would be GLFW
        os.environ["MUJOCO_GL"] = "disable"
        os.environ[DEFERRED] = "1"


def egl_starts() -> bool:
    """Whether a headless EGL display can be initialised, probed in a child process (this
    process maps no EGL library)."""
    try:
        done = subprocess.run([sys.executable, "-c", _EGL_PROBE], capture_output=True,
                              timeout=PROBE_TIMEOUT_S)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0


def choose_gl_backend() -> str | None:
    """The headless backend this machine supports: ``egl`` if an EGL display starts, else
    ``osmesa`` if libOSMesa is installed, else None (rendering then fails with
    :func:`gl_error`'s message, which says what to install)."""
    if egl_starts():
        return "egl"
    if ctypes.util.find_library("OSMesa"):
        return "osmesa"
    return None


def ensure_gl_backend() -> str | None:
    """Before the first render: settle a deferred backend choice and bind MuJoCo's renderer to
    it. Returns the ``MUJOCO_GL`` in effect (None: no backend could be found)."""
    if os.environ.get(DEFERRED) != "1":
        return os.environ.get("MUJOCO_GL")
    backend = choose_gl_backend()
    del os.environ[DEFERRED]
    if backend is None:
        os.environ.pop("MUJOCO_GL", None)
        return None
    os.environ["MUJOCO_GL"] = backend
    if backend == "osmesa":
        os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
    if "mujoco" in sys.modules:  # bound to "disable" at import: bind it to the chosen backend
        importlib.reload(importlib.import_module("mujoco.rendering.classic.gl_context"))
    return backend


def gl_error(err: Exception) -> RuntimeError:
    backend = os.environ.get("MUJOCO_GL", "(unset)")
    return RuntimeError(
        f"render: cannot start an OpenGL context with MUJOCO_GL={backend} ({err}). Headless rendering "
        "needs Mesa EGL (Debian: apt install libegl1 libgl1-mesa-dri) or OSMesa (apt install "
        "libosmesa6, then MUJOCO_GL=osmesa). A MUJOCO_GL you set yourself must be set before "
        "mujoco is imported.")


def point_mediapy_at_ffmpeg(mediapy) -> bool:
    """If ``mediapy`` finds no ``ffmpeg`` (none on ``PATH``, none set), point it at
    imageio-ffmpeg's bundled binary. Returns whether ``mediapy`` can run ffmpeg now."""
    if mediapy.video_is_available():
        return True
    try:
        import imageio_ffmpeg

        mediapy.set_ffmpeg(imageio_ffmpeg.get_ffmpeg_exe())
    except (ImportError, RuntimeError):  # no imageio-ffmpeg, or its binary is missing
        return False
    return mediapy.video_is_available()


def use_bundled_ffmpeg() -> None:
    """Make ``mediapy`` use imageio-ffmpeg's binary when it has no ffmpeg of its own: now if
    ``mediapy`` is imported, else right after it is first imported (see the module docstring)."""
    after_import("mediapy", point_mediapy_at_ffmpeg)


use_bundled_ffmpeg()  # on ``import gripper`` (which imports this module): costs no import of mediapy
