"""How much action noise the grasp survives: the scripted grasp with PPO-like exploration noise.

Drives ``SoftGripperGrasp`` in synergy mode (all servos, lift; no x/y, as issue 25's PPO) with
the scripted grasp of ``scripts/scripted_policy.py`` and adds independent Gaussian noise of
standard deviation ``sigma`` to every action entry at every control step (clipped to the
action box), as a Gaussian policy explores. SB3's PPO starts at sigma = 1 (``log_std_init`` 0).
Prints, per sigma, the share of episodes held and the median dense return, and the same for
uniformly random actions. If a policy that knows the task stops succeeding at the noise an RL
algorithm explores with, the algorithm never sees a success to learn from.

Usage: ``.venv/bin/python scripts/rl_noise_probe.py [--episodes 10] [--sigmas 0,0.1,0.3,0.5,1]
[--channel all|servo|lift]``
"""

from __future__ import annotations

import argparse
import statistics

import gymnasium as gym
import numpy as np
from scripted_policy import ScriptedGrasp

import gripper  # noqa: F401  (registers the environment)

ENV_ID = "gripper:SoftGripperGrasp-v8"


def episode(env, policy, sigma: float | None, seed: int, rng: np.random.Generator,
            channels: slice = slice(None)) -> tuple[bool, float]:
    obs, _ = env.reset(seed=seed)
    policy.reset(obs)
    done, held, ret = False, False, 0.0
    while not done:
        if sigma is None:
            a = env.action_space.sample()
        else:
            a = policy.act(obs)
            noise = np.zeros(a.shape)
            noise[channels] = sigma * rng.standard_normal(a.shape)[channels]
            a = np.clip(a + noise, -1.0, 1.0).astype(np.float32)
        obs, r, term, trunc, info = env.step(a)
        held, ret, done = held or bool(info["is_success"]), ret + float(r), term or trunc
    return held, ret


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=10)
    ap.add_argument("--sigmas", default="0,0.1,0.3,0.5,1")
    ap.add_argument("--object", default="block")
    ap.add_argument("--channel", choices=("all", "servo", "lift"), default="all",
                    help="which action entries get the noise (synergy: 0 servo, 1 lift)")
    args = ap.parse_args()
    env = gym.make(ENV_ID, objects=args.object, action_mode="synergy", palm_control="position",
                   servo_control="position")
    env.action_space.seed(0)
    policy = ScriptedGrasp(env)
    rng = np.random.default_rng(0)
    channels = {"all": slice(None), "servo": slice(0, 1), "lift": slice(1, 2)}[args.channel]
    print(f"{args.object}, synergy actions, noise on {args.channel}, {args.episodes} episodes "
          f"(seeds 0-{args.episodes - 1}) per row")
    for sigma in [*(float(s) for s in args.sigmas.split(",")), None]:
        runs = [episode(env, policy, sigma, seed, rng, channels) for seed in range(args.episodes)]
        label = "random actions" if sigma is None else f"scripted + noise sigma {sigma:g}"
        print(f"{label:<32} held {sum(h for h, _ in runs):>3}/{len(runs)}   median return "
              f"{statistics.median(r for _, r in runs):8.2f}", flush=True)


if __name__ == "__main__":
    main()
