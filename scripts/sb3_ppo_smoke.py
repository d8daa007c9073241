"""Stable-Baselines3 PPO on the environment, with no MUJOCO_GL set: the import-order crash check.

Importing gripper and then PyTorch's optimiser used to kill the interpreter (Mesa's EGL, loaded
by the import-time GL probe, next to triton's native module). This script does what an RL
user's script does, in that order, and trains PPO for a few thousand steps. stable-baselines3
and torch are not dependencies of this project: run it in a venv that has them.

Run: env -u MUJOCO_GL python scripts/sb3_ppo_smoke.py [--steps 4096]
"""

import argparse
import os
import time

import gripper  # noqa: F401  (registers the environment; touches no graphics library)


def mapped_gl() -> list[str]:
    keys = ("libegl", "libgl", "osmesa", "glfw")
    return sorted({ln.split("/")[-1].strip() for ln in open("/proc/self/maps") if any(k in ln.lower() for k in keys)})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=4096)
    args = ap.parse_args()
    print(f"MUJOCO_GL set by the user: {'no' if os.environ.get('GRIPPER_GL_DEFERRED') else 'yes'}")
    import torch
    from stable_baselines3 import PPO
    from stable_baselines3.common.env_util import make_vec_env

    torch.optim.Adam([torch.zeros(1, requires_grad=True)])  # the reported crash point
    env = make_vec_env("gripper:SoftGripperGrasp-v8", n_envs=2, seed=0, env_kwargs={"objects": "block"})
    model = PPO("MlpPolicy", env, n_steps=512, batch_size=128, seed=0, verbose=0, device="cpu")
    t0 = time.perf_counter()
    model.learn(total_timesteps=args.steps)
    wall = time.perf_counter() - t0
    rewards = [ep["r"] for ep in model.ep_info_buffer]
    print(f"torch {torch.__version__}: PPO trained {model.num_timesteps} steps in {wall:.1f} s "
          f"({model.num_timesteps / wall:.0f} steps/s), {len(rewards)} episodes, "
          f"mean episode reward {sum(rewards) / max(1, len(rewards)):.2f}")
    print(f"graphics libraries mapped: {mapped_gl() or 'none'}")


if __name__ == "__main__":
    main()
