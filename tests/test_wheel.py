"""A wheel built from a clean clone, installed in a fresh virtual environment, runs a trial and
the environment from another folder, finds the models and the data, and is never written to.

The fresh environment gets the package from the wheel alone; its dependencies (MuJoCo, NumPy,
Dask, ...) come from this environment's site-packages through a ``.pth`` line, since nothing may
be downloaded here. The editable install's finder is not among them (a ``.pth`` line adds a
folder to ``sys.path`` without running that folder's own ``.pth`` files).
"""

from __future__ import annotations

import shutil
import site
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]

CHECK = """
import json, sys
from pathlib import Path
import gymnasium as gym
import mujoco
import gripper
from gripper import GripperParams, run_trial
from gripper.core.resources import DEFAULT_CALIBRATION_DIR, MODELS_DIR
assert Path(gripper.__file__).is_relative_to(sys.prefix), gripper.__file__
assert not (Path(gripper.__file__).parent / "models").is_symlink()
m = mujoco.MjModel.from_xml_path(str(MODELS_DIR / "soft_gripper" / "scene.xml"))
assert mujoco.MjModel.from_xml_path(str(MODELS_DIR / "pneumatic_gripper" / "scene.xml")).nu == 8
assert (DEFAULT_CALIBRATION_DIR / "calibration.json").is_file()
rec = run_trial("block", seed=0, index=0, params=GripperParams())
env = gym.make("gripper:SoftGripperGrasp-v12", objects="block")
obs, info = env.reset(seed=0)
obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
print(json.dumps({"nu": m.nu, "status": rec.status, "success": rec.success, "obs": len(obs)}))
"""


@pytest.mark.skipif(shutil.which("git") is None or not (ROOT / ".git").exists(), reason="needs a git checkout")
def test_a_wheel_from_a_clean_clone_runs_from_elsewhere(tmp_path):
    clone, dist, venv, elsewhere = (tmp_path / d for d in ("clone", "dist", "venv", "elsewhere"))
    subprocess.run(["git", "clone", "--quiet", str(ROOT), str(clone)], check=True, timeout=300)
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "--no-build-isolation",
                    "-w", str(dist), str(clone)], check=True, timeout=600, capture_output=True)
    wheel = next(dist.glob("gripper-*.whl"))
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=300)
    py = venv / "bin" / "python"
    purelib = subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             check=True, capture_output=True, text=True).stdout.strip()
    (Path(purelib) / "project_dependencies.pth").write_text("\n".join(site.getsitepackages()) + "\n")
    subprocess.run([str(py), "-m", "pip", "install", "--quiet", "--no-deps", "--no-index", str(wheel)],
                   check=True, timeout=300, capture_output=True)
    elsewhere.mkdir()
    done = subprocess.run([str(py), "-c", CHECK], cwd=elsewhere, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert '"nu": 8' in done.stdout and '"status": "ok"' in done.stdout, done.stdout
    # the installed package's models are never written: write-models wants a folder
    cli = venv / "bin" / "gripper"
    refused = subprocess.run([str(cli), "write-models"], cwd=elsewhere, capture_output=True, text=True, timeout=300)
    assert refused.returncode == 2 and "--out" in refused.stderr, refused.stderr
    written = subprocess.run([str(cli), "write-models", "--out", "mine"], cwd=elsewhere, capture_output=True,
                             text=True, timeout=300)
    assert written.returncode == 0 and (elsewhere / "mine" / "scene.xml").is_file(), written.stderr
    assert list(elsewhere.iterdir()) == [elsewhere / "mine"]  # and nothing else (no MUJOCO_LOG.TXT)
