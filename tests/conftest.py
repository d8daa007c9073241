"""Headless rendering in tests: MuJoCo picks its OpenGL backend when it is first imported, and
test modules may import mujoco before gripper."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import ctypes.util  # noqa: E402

import pytest  # noqa: E402

# Rendering tests need an OpenGL library (Mesa EGL or OSMesa; no display or GPU). Where neither
# is installed at all they are skipped with the reason, never reported as passed.
HAVE_GL = bool(ctypes.util.find_library("EGL") or ctypes.util.find_library("OSMesa"))
needs_gl = pytest.mark.skipif(not HAVE_GL, reason="no OpenGL library (install libegl1 or libosmesa6)")
