"""Stable-Baselines3 PPO on the environment with no MUJOCO_GL set: the import-order crash check
(slow; it was ``scripts/sb3_ppo_smoke.py`` until 0.17.0).

Importing gripper and then PyTorch's optimiser used to kill the interpreter (Mesa's EGL, loaded
by an import-time GL probe, next to triton's native module). This does what an RL user's script
does, in that order, in a fresh interpreter, and trains PPO for a few thousand steps.
stable-baselines3 and torch are the ``rl`` extra's, not the test environment's: without them
the test is skipped.
"""

import os
import subprocess
import sys

import pytest

SCRIPT = """
import gripper  # registers the environment; touches no graphics library
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.env_util import make_vec_env

torch.optim.Adam([torch.zeros(1, requires_grad=True)])  # the reported crash point
env = make_vec_env("gripper:SoftGripperGrasp-v12", n_envs=2, seed=0, env_kwargs={"objects": "block"})
model = PPO("MlpPolicy", env, n_steps=512, batch_size=128, seed=0, verbose=0, device="cpu")
model.learn(total_timesteps=2048)
print(model.num_timesteps)
"""


@pytest.mark.slow
def test_ppo_trains_after_importing_gripper_first():
    pytest.importorskip("stable_baselines3")
    pytest.importorskip("torch")
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    done = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=900, env=env)
    assert done.returncode == 0, done.stderr[-2000:]
    assert int(done.stdout.split()[-1]) >= 2048
