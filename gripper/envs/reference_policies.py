"""Reference policies of the environment's reward ladder: hovering, touching and holding,
each a rung a learner passes on its way from the start to a held grasp.

Each is a policy of the observation alone (a batch of observations to a batch of velocity
actions), built on :class:`gripper.envs.scripted_grasp.ScriptedGrasp`:

- ``idle``: no action: the palm stays at its start, the fingers open;
- ``hover_closed``: the local optimum Stable-Baselines3's PPO and SAC settled in on v7 (issue
  49): the fingers close at once and the palm comes down until a finger presses on the
  object (or the grasp height is reached), and stays there;
- ``hover_open``: the palm comes down to the grasp height with the fingers open and stays;
- ``touch``: the scripted grasp without its lift: down, close until the grip tension, stay;
- ``hold``: the scripted grasp (down, close, lift, hold).

``docs/environment.md`` ("The reward ladder") lists their returns under the dense reward of v11
and of v12, side by side (:func:`ladder_returns`, printed by ``scripts/reward_ladder.py``), and
``tests/test_reward_ladder.py`` holds the ladder's order.

Example:
    >>> import gymnasium as gym                                                    # doctest: +SKIP
    >>> envs = gym.make_vec("gripper:SoftGripperGrasp-v12", num_envs=4, action_mode="synergy",
    ...                     vectorization_mode="vector_entry_point")              # doctest: +SKIP
    >>> policy = reference_policy("touch", envs.unwrapped.config)                 # doctest: +SKIP
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from gripper.envs.config import CONTACT_FORCE, EnvConfig
from gripper.envs.scripted_grasp import ScriptedGrasp

LADDER = ("idle", "hover_closed", "hover_open", "touch", "hold")


def reference_policy(name: str, config: EnvConfig) -> Callable[[np.ndarray], np.ndarray]:
    """The reference policy ``name`` (one of :data:`LADDER`) for an environment made with
    ``config`` (velocity actions, a cable drive: :class:`ScriptedGrasp`'s conditions).

    Raises:
        ValueError: an unknown name (the allowed ones named), or an environment the scripted
            grasp cannot drive.
    """
    if name not in LADDER:
        raise ValueError(f"policy: must be one of {', '.join(LADDER)}, got {name!r}")
    script = ScriptedGrasp(config)
    k = script.n_servo

    def idle(obs):
        return np.zeros((len(np.atleast_2d(obs)), config.action_size), dtype=np.float32)

    def hover_closed(obs):
        obs = np.atleast_2d(obs)
        a = idle(obs)
        palm = script._part(obs, "palm_setpoint")[:, 2]
        touching = (script._part(obs, "finger_object_force") > CONTACT_FORCE).any(axis=1)
        a[:, :k] = 1.0  # close at the servo's slew rate, from the first step
        down = np.clip((script.z_grasp - palm) / script.palm_step, -1.0, 0.0)
        a[:, k] = np.where(touching, 0.0, down)
        return a

    def hover_open(obs):
        obs = np.atleast_2d(obs)
        a = idle(obs)
        palm = script._part(obs, "palm_setpoint")[:, 2]
        a[:, k] = np.clip((script.z_grasp - palm) / script.palm_step, -1.0, 0.0)
        return a

    def touch(obs):
        a = script(obs)
        a[:, k] = np.minimum(a[:, k], 0.0)  # never lifts
        return a

    policies: dict[str, Callable[[np.ndarray], np.ndarray]] = {
        "idle": idle, "hover_closed": hover_closed, "hover_open": hover_open, "touch": touch, "hold": script}
    return policies[name]


# v11's dense reward (0.21.0), recomputed from a v12 step for the side-by-side table: reach paid
# whatever the fingers did, touch paid nothing
V11_WEIGHTS = {"reach": 0.125, "lift": 0.25, "success": 0.625, "damage": 1.25, "action": 0.00125}


def ladder_returns(episodes: int = 8, seed: int = 0, **env_kwargs) -> dict[str, dict[str, float]]:
    """Mean episode return of each reference policy (:data:`LADDER`) in ``SoftGripperGrasp``
    made with ``env_kwargs`` (velocity actions, dense reward), under the environment's reward and
    under v11's (``V11_WEIGHTS``; its reach term recomputed from the observed distance, its lift
    from the object's rise), with each policy's success rate:
    ``{name: {"return": .., "return_v11": .., "success": ..}}``. Episode ``k`` has seed
    ``seed + k`` for every policy."""
    import gymnasium as gym

    from gripper.envs.config import HELD, REACH_SCALE
    from gripper.envs.registration import ENV_ID

    venv = gym.make_vec(f"gripper:{ENV_ID}", num_envs=episodes, vectorization_mode="vector_entry_point",
                        nthread=1, **env_kwargs)
    cfg = venv.config  # type: ignore[attr-defined]
    script = ScriptedGrasp(cfg)
    grasp_point = np.array([0.0, 0.0, -0.5 * (script.z_grasp - HELD.tip_clearance)])  # mid-finger
    w = V11_WEIGHTS
    out: dict[str, dict[str, float]] = {}
    try:
        for name in LADDER:
            policy = reference_policy(name, cfg)
            obs, _ = venv.reset(seed=seed)
            alive = np.ones(episodes, dtype=bool)
            ret, ret11, held = np.zeros(episodes), np.zeros(episodes), np.zeros(episodes, dtype=bool)
            while alive.any():
                act = policy(obs)
                obs, reward, term, trunc, info = venv.step(act)
                d = np.linalg.norm(script._part(obs, "object_pos_rel_palm") - grasp_point, axis=1)
                rise = np.clip(np.asarray(info["object_height_m"]) / HELD.success_height, 0.0, 1.0)
                r11 = (w["reach"] * (1.0 - np.tanh(d / REACH_SCALE)) + w["lift"] * rise
                       + w["success"] * np.asarray(info["is_success"], dtype=float)
                       - w["damage"] * (np.asarray(info["reward_damage"]) < 0)
                       - w["action"] * np.sum(np.asarray(act, dtype=float) ** 2, axis=1))
                ret += np.where(alive, reward, 0.0)
                ret11 += np.where(alive, r11, 0.0)
                held |= alive & np.asarray(info["is_success"], dtype=bool)
                alive &= ~(term | trunc)
            out[name] = {"return": float(ret.mean()), "return_v11": float(ret11.mean()),
                         "success": float(held.mean())}
    finally:
        venv.close()
    return out
