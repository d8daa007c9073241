"""Choice of the headless OpenGL backend (no rendering needed)."""

import gripper.render.backend as R


def test_user_choice_is_kept(monkeypatch):
    monkeypatch.setenv("MUJOCO_GL", "osmesa")
    monkeypatch.setattr(R, "egl_starts", lambda: True)
    assert R.choose_gl_backend() == "osmesa"


def test_egl_then_osmesa_then_unset(monkeypatch):
    monkeypatch.delenv("MUJOCO_GL", raising=False)
    monkeypatch.setattr(R, "egl_starts", lambda: True)
    assert R.choose_gl_backend() == "egl"
    monkeypatch.delenv("MUJOCO_GL")
    monkeypatch.setattr(R, "egl_starts", lambda: False)
    monkeypatch.setattr(R.ctypes.util, "find_library", lambda name: "libOSMesa.so" if name == "OSMesa" else None)
    monkeypatch.delenv("PYOPENGL_PLATFORM", raising=False)
    assert R.choose_gl_backend() == "osmesa"
    monkeypatch.delenv("MUJOCO_GL")
    monkeypatch.setattr(R.ctypes.util, "find_library", lambda name: None)
    assert R.choose_gl_backend() is None


def test_gl_error_says_what_to_install():
    msg = str(R.gl_error(RuntimeError("no display")))
    assert "libegl1" in msg and "libosmesa6" in msg and "\n" not in msg
