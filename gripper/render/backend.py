"""The OpenGL backend for headless rendering, chosen before MuJoCo is imported.

``MUJOCO_GL`` if the user set it, else ``egl`` (software Mesa EGL works with no display and no
GPU), else ``osmesa`` where only that library is installed."""

from __future__ import annotations

import ctypes.util
import os


def choose_gl_backend() -> str | None:
    """Set ``MUJOCO_GL`` unless the user did: ``egl`` if an EGL display starts, else ``osmesa``
    if libOSMesa is installed, else leave it unset (rendering then fails with :func:`gl_error`'s
    message, which says what to install). Must run before ``import mujoco``; returns the value in
    effect."""
    if "MUJOCO_GL" not in os.environ:
        if egl_starts():
            os.environ["MUJOCO_GL"] = "egl"
        elif ctypes.util.find_library("OSMesa"):
            os.environ["MUJOCO_GL"] = "osmesa"
            os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
    return os.environ.get("MUJOCO_GL")


def egl_starts() -> bool:
    """Whether a headless EGL display can be initialised, the way MuJoCo's EGL backend opens one
    (an EGL device via ``eglQueryDevicesEXT`` / ``eglGetPlatformDisplayEXT``); about 0.1 s with
    Mesa's software EGL. Uses ctypes only, so it can run before anything imports OpenGL."""
    name = ctypes.util.find_library("EGL")
    if not name:
        return False
    try:
        lib = ctypes.CDLL(name)
        lib.eglGetProcAddress.restype = ctypes.c_void_p
        lib.eglGetProcAddress.argtypes = [ctypes.c_char_p]
        lib.eglInitialize.restype = ctypes.c_uint
        lib.eglInitialize.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
        lib.eglTerminate.argtypes = [ctypes.c_void_p]
        q = lib.eglGetProcAddress(b"eglQueryDevicesEXT")
        g = lib.eglGetProcAddress(b"eglGetPlatformDisplayEXT")
        if not (q and g):
            return False
        query = ctypes.CFUNCTYPE(ctypes.c_uint, ctypes.c_int, ctypes.POINTER(ctypes.c_void_p),
                                 ctypes.POINTER(ctypes.c_int))(q)
        get_display = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_void_p)(g)
        devices = (ctypes.c_void_p * 16)()
        n = ctypes.c_int(0)
        if not query(16, devices, ctypes.byref(n)):
            return False
        for i in range(n.value):
            dpy = get_display(0x313F, devices[i], None)  # EGL_PLATFORM_DEVICE_EXT
            if dpy and lib.eglInitialize(dpy, None, None):
                lib.eglTerminate(dpy)
                return True
    except (OSError, AttributeError):
        return False
    return False


def gl_error(err: Exception) -> RuntimeError:
    backend = os.environ.get("MUJOCO_GL", "(unset)")
    return RuntimeError(
        f"render: cannot start an OpenGL context with MUJOCO_GL={backend} ({err}). Headless rendering "
        "needs Mesa EGL (Debian: apt install libegl1 libgl1-mesa-dri) or OSMesa (apt install "
        "libosmesa6, then MUJOCO_GL=osmesa). MUJOCO_GL must be set before mujoco is imported: "
        "import gripper first, or export MUJOCO_GL=egl.")
