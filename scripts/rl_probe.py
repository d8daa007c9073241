"""Why PPO does or does not learn the grasp: learning curves of one variant at a time.

Trains Stable-Baselines3 PPO (default hyper-parameters but for ``--n-envs`` envs through the
native vector env's SB3 adapter) on ``SoftGripperGrasp`` and, every ``--every`` steps, records
the training episodes' success rate and return (SB3's episode buffers, last 100 episodes) and the
deterministic policy's success over ``--eval`` episodes with seeds never used in training.
Writes one CSV row per checkpoint to ``--out`` and prints them. Needs the ``rl`` extra.

The variants before ``v4`` were measured on ``SoftGripperGrasp-v3`` (package 0.10.0). They now
run on v4 with v3's palm set-points and success rule (``V3``), but v4's reach and contact
terms, so their curves are not v3's exactly; ``git checkout`` 0.10.0 to repeat them as they were.
``gripper train`` is the entry point for v4 itself; ``v4`` and ``v4_tuned`` here are its first
probes (SB3's default hyper-parameters, and the baselines' ``n_steps``/``batch_size`` with
``VecNormalize``).

Variants (``--variant``), each one change from ``issue`` (the setup of issue 25: block, synergy
actions, dense reward):

- ``issue``: as the environment ships;
- ``normalize``: SB3's ``VecNormalize`` on observations and rewards (observation scales span
  newtons, metres and radians per second);
- ``sparse``: the sparse reward (1 per held step);
- ``short``: episodes of 150 control steps (3 s) instead of 300;
- ``lowstd``: PPO's exploration noise started at sigma 0.135 (``log_std_init`` -2, SB3's default
  0) instead of the environment changed: ``scripts/rl_noise_probe.py`` shows the scripted grasp
  surviving lift noise of sigma 0.1 but not 0.3;
- ``rate``: the lift action read as a rate (at most :data:`LIFT_RATE` m/s, integrated into the
  height set-point by :class:`LiftRate`, a Gymnasium wrapper here, not in the package), so that
  exploration noise becomes a slow random walk of the palm; single envs in SB3's
  ``DummyVecEnv``, since the wrapper sits on each env;
- ``noterm``: the episode does not end on success (``terminate_on_success=False``): with the
  dense reward's positive per-step lift term, ending the episode on success forfeits the lift
  reward of every remaining step, so a policy that hovers just under the success height earns
  more than one that succeeds;
- ``rate_noterm``: ``rate`` and ``noterm`` together.

Usage: ``.venv/bin/python scripts/rl_probe.py --variant issue --steps 150000 --out runs/rl/issue.csv``
"""

from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import VecMonitor, VecNormalize

import gripper  # noqa: F401  (registers the environment)
from gripper.envs.registration import ENV_ID
from gripper.envs.sb3 import make_sb3_vec_env

LIFT_RATE = 0.10  # m/s at action +-1: the scripted grasp's lift and approach speed


class LiftRate(gym.Wrapper):
    """Synergy actions (servo, lift rate): the lift entry in [-1, 1] is a rate of at most
    :data:`LIFT_RATE`, integrated into the palm height set-point (kept in the lift's range)."""

    def __init__(self, env):
        super().__init__(env)
        u = env.unwrapped
        self._i_height = u.observation_structure["palm_height"][0]
        self._dt = u.config.control_period
        self._lift = 0.0
        self._step = 0.0

    def reset(self, **kwargs):
        obs, info = self.env.reset(**kwargs)
        u = self.env.unwrapped
        per_m = (u.lift_action(0.20) - u.lift_action(0.15)) / 0.05  # action units per metre
        self._step = LIFT_RATE * self._dt * per_m
        self._lift = u.lift_action(float(obs[self._i_height]))
        return obs, info

    def step(self, action):
        self._lift = float(np.clip(self._lift + np.clip(action[1], -1.0, 1.0) * self._step, -1.0, 1.0))
        a = np.array(action, dtype=np.float32).copy()
        a[1] = self._lift
        return self.env.step(a)


VARIANTS: dict[str, dict] = {
    "issue": {},
    "normalize": {},
    "sparse": {"reward_type": "sparse"},
    "short": {"max_episode_steps": 150},
    "lowstd": {},
    "rate": {},
    "noterm": {"terminate_on_success": False},
    "rate_noterm": {"terminate_on_success": False},
    "v4": {},
    "v4_tuned": {},
}
# the variants before v4 ran the environment as it was: absolute palm set-points, the episode
# ended on success, the reach term -1 x distance [m]
V3 = {"palm_control": "position", "servo_control": "position", "terminate_on_success": True,
      "reward_weights": {"contact": 0.25}}
PPO_KWARGS: dict[str, dict] = {"lowstd": {"policy_kwargs": {"log_std_init": -2.0}},
                               "v4_tuned": {"n_steps": 256, "batch_size": 256}}
EVAL_SEED = 10_000  # evaluation episodes use seeds from here on: never a training seed


def evaluate(model: PPO, env_kwargs: dict, episodes: int, norm: VecNormalize | None, rate: bool) -> float:
    """Share of ``episodes`` (unseen seeds) in which the deterministic policy held the grasp."""
    venv = (make_vec_env(lambda: gym.make(ENV_ID, **env_kwargs), n_envs=1, wrapper_class=LiftRate)
            if rate else make_sb3_vec_env(num_envs=1, nthread=1, **env_kwargs))
    held = 0
    for k in range(episodes):
        venv.seed(EVAL_SEED + k)
        obs = venv.reset()
        done = np.array([False])
        while not done[0]:
            o = norm.normalize_obs(obs) if norm is not None else obs
            action, _ = model.predict(o, deterministic=True)
            obs, _, done, infos = venv.step(action)
        held += bool(infos[0].get("is_success"))
    venv.close()
    return held / episodes


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--variant", choices=sorted(VARIANTS), default="issue")
    ap.add_argument("--steps", type=int, default=150_000)
    ap.add_argument("--every", type=int, default=25_000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--n-envs", type=int, default=8)
    ap.add_argument("--eval", type=int, default=20)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    torch.set_num_threads(1)
    base = {} if args.variant.startswith("v4") else V3
    env_kwargs = {"objects": "block", "action_mode": "synergy", "scale_observations": False,  # SI values
                  **base, **VARIANTS[args.variant]}
    if args.variant.startswith("rate"):
        venv = VecMonitor(make_vec_env(lambda: gym.make(ENV_ID, **env_kwargs), n_envs=args.n_envs,
                                       wrapper_class=LiftRate))
    else:
        venv = VecMonitor(make_sb3_vec_env(num_envs=args.n_envs, nthread=1, **env_kwargs))
    norm = None
    if args.variant in ("normalize", "v4_tuned"):
        norm = VecNormalize(venv, norm_obs=True, norm_reward=True)
    model = PPO("MlpPolicy", norm or venv, seed=args.seed, device="cpu", verbose=0,
                **PPO_KWARGS.get(args.variant, {}))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        print("env", env_kwargs, "ppo", PPO_KWARGS.get(args.variant, {}), flush=True)
        w.writerow(["variant", "seed", "steps", "wall_s", "train_success", "train_return", "eval_success"])
        done = 0
        while done < args.steps:
            model.learn(args.every, reset_num_timesteps=False)
            done = model.num_timesteps
            if norm is not None:
                norm.training = False
            succ = float(np.mean(model.ep_success_buffer)) if model.ep_success_buffer else float("nan")
            ret = float(np.mean([e["r"] for e in model.ep_info_buffer])) if model.ep_info_buffer else float("nan")
            ev = evaluate(model, env_kwargs, args.eval, norm, args.variant.startswith("rate"))
            if norm is not None:
                norm.training = True
            row = [args.variant, args.seed, done, round(time.perf_counter() - t0, 1), round(succ, 3),
                   round(ret, 2), ev]
            w.writerow(row)
            f.flush()
            print(*row, flush=True)


if __name__ == "__main__":
    main()
