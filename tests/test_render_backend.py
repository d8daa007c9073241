"""Choice of the headless OpenGL backend: deferred until something renders, probed in a child
process, and never a graphics library in a process that only simulates."""

import os
import subprocess
import sys

import gripper.render.backend as R

GL_LIBS = ("libegl", "libgl", "osmesa", "glfw", "libglx")

MAPPED = f"""
GL_LIBS = {GL_LIBS!r}
def gl():
    return sorted({{l.split('/')[-1].strip() for l in open('/proc/self/maps')
                   if any(k in l.lower() for k in GL_LIBS)}})
"""


def _fresh(code: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", R.DEFERRED, "PYOPENGL_PLATFORM")}
    return subprocess.run([sys.executable, "-c", MAPPED + code], env=env, capture_output=True, text=True,
                          timeout=300)


def test_user_choice_is_kept(monkeypatch):
    monkeypatch.setenv("MUJOCO_GL", "osmesa")
    monkeypatch.delenv(R.DEFERRED, raising=False)
    R.defer_gl_backend()
    assert os.environ["MUJOCO_GL"] == "osmesa" and R.DEFERRED not in os.environ
    assert R.ensure_gl_backend() == "osmesa"


def test_egl_then_osmesa_then_none(monkeypatch):
    monkeypatch.setattr(R, "egl_starts", lambda: True)
    assert R.choose_gl_backend() == "egl"
    monkeypatch.setattr(R, "egl_starts", lambda: False)
    monkeypatch.setattr(R.ctypes.util, "find_library", lambda name: "libOSMesa.so" if name == "OSMesa" else None)
    assert R.choose_gl_backend() == "osmesa"
    monkeypatch.setattr(R.ctypes.util, "find_library", lambda name: None)
    assert R.choose_gl_backend() is None


def test_gl_error_says_what_to_install():
    msg = str(R.gl_error(RuntimeError("no display")))
    assert "libegl1" in msg and "libosmesa6" in msg and "\n" not in msg


def test_simulating_maps_no_graphics_library():
    """A fresh interpreter without MUJOCO_GL: import gripper, make and step the environment."""
    out = _fresh("""
import gripper, gymnasium as gym
env = gym.make("gripper:SoftGripperGrasp-v12", objects="block")
env.reset(seed=0)
for _ in range(3):
    env.step(env.action_space.sample())
print(gl())
assert gl() == [], gl()
""")
    assert out.returncode == 0, out.stdout + out.stderr


def test_rendering_works_headless_by_default():
    """The same interpreter renders once it is asked to: the backend is chosen then."""
    out = _fresh("""
import gripper, gymnasium as gym
env = gym.make("gripper:SoftGripperGrasp-v12", objects="block", render_mode="rgb_array", width=64, height=48)
env.reset(seed=0)
assert gl() == [], gl()
img = env.render()
assert img.shape == (48, 64, 3) and img.max() > 0, img.shape
print(gl())
""")
    assert out.returncode == 0, out.stdout + out.stderr
