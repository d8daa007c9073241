"""Headless rendering in tests: MuJoCo picks its OpenGL backend when it is first imported, and
test modules may import mujoco before gripper."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")
