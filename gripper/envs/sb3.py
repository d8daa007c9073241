"""Stable-Baselines3 on the native vector environment: an SB3 ``VecEnv`` over it.

SB3 takes its own ``VecEnv`` type, not a Gymnasium ``VectorEnv``, so the native vector
environment (:mod:`gripper.envs.vector_env`, one ``mujoco.rollout`` call per control step for
all slots) needs this adapter. Needs the ``rl`` extra (``pip install -e ".[rl]"``:
stable-baselines3 and the CPU build of PyTorch).

What changes between the two conventions, and how:

- **Autoreset.** The native env resets a finished slot on the *next* step (Gymnasium's
  ``NEXT_STEP``); SB3 expects the new episode's first observation in the *same* step, with the
  last one in ``infos[i]["terminal_observation"]``. The adapter resets finished slots at once
  (``reset(options={"reset_mask": done})``), so no step is spent on a reset and every action
  reaches the physics.
- **Truncation.** ``done`` is terminated or truncated; ``infos[i]["TimeLimit.truncated"]`` is
  true where the episode hit its step limit without terminating (SB3 bootstraps those).
- **Infos.** Gymnasium's dict of arrays with ``_key`` masks becomes SB3's list of per-env
  dicts; ``is_success`` is there at an episode's end, so SB3's success-rate logging works.
- **Goal-conditioned observations.** A dict observation (``SoftGripperGraspGoal``) passes
  through as SB3's dict of arrays, ``terminal_observation`` as one slot's dict; ``compute_reward``
  is reached by ``env_method``, as SB3's ``HerReplayBuffer`` calls it.
- **Seeding.** ``seed(s)`` seeds the next ``reset()``: slot ``i`` then runs the episode a single
  environment reset with seed ``s + i`` runs (the native env's convention, and SB3's).

``get_attr`` and ``set_attr`` act on the vector environment as a whole (one value repeated per
slot); ``env_method`` calls a method of it once and repeats the result per slot. Rendering shows
slot 0.

Example:
    >>> from gripper.envs.sb3 import make_sb3_vec_env                         # doctest: +SKIP
    >>> from stable_baselines3 import PPO                                     # doctest: +SKIP
    >>> venv = make_sb3_vec_env(num_envs=8, objects="block")                  # doctest: +SKIP
    >>> PPO("MlpPolicy", venv, seed=0).learn(10_000)                          # doctest: +SKIP
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from stable_baselines3.common.vec_env import VecEnv

from gripper.envs.registration import ENV_ID


def split_infos(info: dict, n: int) -> list[dict]:
    """Gymnasium's vector info (``info[k]`` array, ``info["_k"]`` mask; dicts nested the same
    way) as ``n`` per-env dicts holding only the keys each env set."""
    out: list[dict] = [{} for _ in range(n)]
    for k, v in info.items():
        if k.startswith("_"):
            continue
        mask = info.get("_" + k)
        per_env = split_infos(v, n) if isinstance(v, dict) else None
        for i in range(n):
            if mask is not None and not mask[i]:
                continue
            if per_env is not None:
                out[i][k] = per_env[i]
            else:
                item = v[i]
                out[i][k] = item.item() if isinstance(item, np.generic) else item
    return out


def _item(obs, i: int):
    """Slot ``i``'s observation (an array, or a dict of arrays for a goal-conditioned env)."""
    return {k: v[i].copy() for k, v in obs.items()} if isinstance(obs, dict) else obs[i].copy()


def _where(mask: np.ndarray, a, b):
    """``a`` where ``mask`` (per slot), else ``b``; arrays or dicts of arrays."""
    if isinstance(a, dict):
        return {k: np.where(mask.reshape(-1, *([1] * (np.ndim(a[k]) - 1))), a[k], b[k]) for k in a}
    return np.where(mask.reshape(-1, *([1] * (np.ndim(a) - 1))), a, b)


class SB3VecEnv(VecEnv):
    """SB3 ``VecEnv`` over a Gymnasium vector environment with ``NEXT_STEP`` autoreset and
    ``reset_mask`` support (the native :class:`gripper.envs.vector_env.SoftGripperGraspVectorEnv`)."""

    def __init__(self, venv: Any):
        self.venv = venv
        self._actions: np.ndarray | None = None
        super().__init__(venv.num_envs, venv.single_observation_space, venv.single_action_space)

    def reset(self) -> np.ndarray:
        seeds = None if all(s is None for s in self._seeds) else list(self._seeds)
        if any(self._options):
            raise ValueError("set_options: the grasp environment takes no reset options")
        obs, info = self.venv.reset(seed=seeds)
        self.reset_infos = split_infos(info, self.num_envs)
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions)

    def step_wait(self):
        if self._actions is None:
            raise RuntimeError("step_wait: call step_async(actions) first")
        obs, rewards, terminated, truncated, info = self.venv.step(self._actions)
        self._actions = None
        infos = split_infos(info, self.num_envs)
        dones = terminated | truncated
        if dones.any():
            for i in np.flatnonzero(dones):
                infos[i]["terminal_observation"] = _item(obs, i)
                infos[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            fresh, reset_info = self.venv.reset(options={"reset_mask": dones})
            obs = _where(dones, fresh, obs)
            for i, r in enumerate(split_infos(reset_info, self.num_envs)):
                if dones[i]:
                    self.reset_infos[i] = r
        return obs, rewards.astype(np.float32), dones, infos

    def close(self) -> None:
        self.venv.close()

    def get_attr(self, attr_name: str, indices=None) -> list[Any]:
        return [getattr(self.venv, attr_name)] * len(list(self._get_indices(indices)))

    def set_attr(self, attr_name: str, value: Any, indices=None) -> None:
        setattr(self.venv, attr_name, value)

    def env_method(self, method_name: str, *method_args, indices=None, **method_kwargs) -> list[Any]:
        result = getattr(self.venv, method_name)(*method_args, **method_kwargs)
        return [result] * len(list(self._get_indices(indices)))

    def env_is_wrapped(self, wrapper_class: type, indices=None) -> list[bool]:
        return [False] * len(list(self._get_indices(indices)))

    def get_images(self) -> Sequence[np.ndarray | None]:
        return [self.venv.render()] + [None] * (self.num_envs - 1)


def make_sb3_vec_env(num_envs: int = 8, env_id: str = ENV_ID, **env_kwargs: Any) -> SB3VecEnv:
    """``num_envs`` slots of the native vector environment ``env_id`` (``SoftGripperGrasp`` or
    its goal-conditioned variant; their keyword arguments in ``env_kwargs``) behind :class:`SB3VecEnv`."""
    import gymnasium

    venv = gymnasium.make_vec(f"gripper:{env_id}", num_envs=num_envs, vectorization_mode="vector_entry_point",
                              **env_kwargs)
    return SB3VecEnv(venv)
