"""The deterministic policy's success over episodes with seeds never used in training.

An episode counts as a success when the grasp was held (``info["is_success"]``: the benchmark's
definition, lifted at least 8 cm for 1 s without slipping 20 mm and without damage) at some
step. The episodes run together in one native vector environment: slot ``i`` runs the episode
of seed ``first_seed + i``, the one a single environment reset with that seed runs.

Example:
    >>> from gripper.rl.evaluation import evaluate_policy                              # doctest: +SKIP
    >>> evaluate_policy(lambda obs: obs[:, :2] * 0, {"objects": ("block",),
    ...                 "action_mode": "synergy"}, episodes=4)["success"]               # doctest: +SKIP
    0.0
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from gripper.rl.config import EVAL_SEED

BATCH = 50  # episodes stepped together at most


def make_eval_env(env_kwargs: dict[str, Any], episodes: int, env_id: str | None = None, nthread: int = 1):
    """A native vector env of ``env_id`` (default ``SoftGripperGrasp``) with one slot per episode
    of a batch (``nthread`` MuJoCo threads)."""
    import gymnasium as gym

    from gripper.envs.registration import ENV_ID

    return gym.make_vec(f"gripper:{env_id or ENV_ID}", num_envs=min(BATCH, episodes),
                        vectorization_mode="vector_entry_point", nthread=nthread, **env_kwargs)


def evaluate_policy(act: Callable[[Any], np.ndarray], env_kwargs: dict[str, Any], episodes: int = 50,
                    first_seed: int = EVAL_SEED, venv=None, env_id: str | None = None) -> dict[str, Any]:
    """Run ``episodes`` episodes (seeds ``first_seed`` on) with ``act`` (a batch of observations
    to a batch of actions); return the success rate, the rate per object and the mean return.

    ``venv``: a vector env from :func:`make_eval_env` to reuse (built and closed here if None,
    of ``env_id``). In the goal-conditioned env an episode succeeds when its goal is met at its
    last step (Gymnasium-Robotics' rule), elsewhere when the grasp was held at some step.
    """
    own = venv is None
    if own:
        venv = make_eval_env(env_kwargs, episodes, env_id)
    final_step = hasattr(venv, "compute_reward")  # a goal-conditioned env: Fetch's rule
    n = venv.num_envs
    success: list[bool] = []
    objects: list[str] = []
    returns: list[float] = []
    try:
        for start in range(0, episodes, n):
            k = min(n, episodes - start)
            obs, info = venv.reset(seed=first_seed + start)
            obj = list(info["object"])
            alive = np.ones(n, dtype=bool)
            alive[k:] = False
            held = np.zeros(n, dtype=bool)
            ret = np.zeros(n)
            while alive.any():
                obs, reward, term, trunc, info = venv.step(np.asarray(act(obs)))
                ret += np.where(alive, reward, 0.0)
                now = np.asarray(info.get("is_success", np.zeros(n, dtype=bool)), dtype=bool)
                held = np.where(alive, now, held) if final_step else held | (alive & now)
                alive &= ~(term | trunc)
            success += held[:k].tolist()
            objects += obj[:k]
            returns += ret[:k].tolist()
    finally:
        if own:
            venv.close()
    by_object = {o: float(np.mean([s for s, oo in zip(success, objects, strict=True) if oo == o]))
                 for o in sorted(set(objects))}
    return {"success": float(np.mean(success)), "by_object": by_object, "return": float(np.mean(returns)),
            "episodes": episodes}
