"""Stable-Baselines3 vectorisation: the adapter over the native vector env against SB3's own
``make_vec_env`` (``DummyVecEnv``, one process; ``SubprocVecEnv``, one process per env), side by
side, as SB3 steps them (``VecEnv.step`` with random actions, same-step autoreset).

Random actions on the block, 20 ms control period; environment steps per second, medians of
``--repeats`` runs, the three run back to back in each repeat. Needs the ``rl`` extra.

Run: .venv/bin/python scripts/bench_sb3_vec.py [--num-envs 8] [--steps 200] [--repeats 3]
"""

from __future__ import annotations

import argparse
import statistics
import time

import gymnasium as gym
import numpy as np
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import SubprocVecEnv

import gripper  # noqa: F401  (registers the environment)
from gripper.envs.sb3 import make_sb3_vec_env

ENV_ID = "gripper:SoftGripperGrasp-v12"


def rate(venv, steps: int, seed: int = 0) -> float:
    venv.seed(seed)
    venv.reset()
    rng = np.random.default_rng(seed)
    acts = rng.uniform(-1, 1, (steps, venv.num_envs) + venv.action_space.shape).astype(np.float32)
    t0 = time.perf_counter()
    for a in acts:
        venv.step(a)
    return steps * venv.num_envs / (time.perf_counter() - t0)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--num-envs", type=int, default=8)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    n, kw = args.num_envs, {"objects": "block"}
    makers = {
        "adapter (native vector env)": lambda: make_sb3_vec_env(num_envs=n, **kw),
        "SB3 DummyVecEnv": lambda: make_vec_env(lambda: gym.make(ENV_ID, **kw), n_envs=n),
        "SB3 SubprocVecEnv": lambda: make_vec_env(lambda: gym.make(ENV_ID, **kw), n_envs=n,
                                                  vec_env_cls=SubprocVecEnv),
    }
    rates: dict[str, list[float]] = {k: [] for k in makers}
    for _ in range(args.repeats):
        for name, make in makers.items():
            venv = make()
            rates[name].append(rate(venv, args.steps))
            venv.close()
    base = statistics.median(rates["adapter (native vector env)"])
    print(f"{n} envs, {args.steps} steps each, medians of {args.repeats}")
    for name, r in rates.items():
        med = statistics.median(r)
        print(f"{name:<28} {med:8.0f} steps/s   adapter / this: {base / med:5.2f}")


if __name__ == "__main__":
    main()
