"""Demonstrations of the scripted grasp, and behaviour-cloning pre-training from them: how
``gripper train --demos N`` gets its policy across the dead zone where closing the fingers
changes nothing until they touch the object (``docs/environment.md``).

The recipe, standard in RL from demonstrations:

1. **Demonstrations** (:func:`collect_demonstrations`): ``N`` episodes of
   :class:`gripper.envs.scripted_grasp.ScriptedGrasp` in the training task, with DART's noise
   injection (Laskey et al., 2017: the executed action is the demonstrator's plus Gaussian noise
   of ``noise`` standard deviation, the label the demonstrator's own), so that the demonstrations
   also show how to recover from the deviations a learner makes. Their environment steps count
   in the run's budget (``demo_steps`` in ``progress.csv``).
2. **Behaviour cloning** (:func:`pretrain`): the policy's mean action regressed on the labels
   (mean squared error, Adam), as Pomerleau's and the ``imitation`` library's BC do. For PPO the
   value network is regressed on the demonstrations' discounted returns at the same time, so
   that the first policy-gradient updates see advantages and not an untrained critic's noise
   (the advice of Rajeswaran et al., 2018, DAPG, for fine-tuning a cloned policy). For SAC the
   demonstrations also go into the replay buffer (as in DDPGfD, Večerík et al., 2017).
3. **Reinforcement learning** from there, unchanged: PPO or SAC with their hyper-parameters,
   starting from the cloned policy with the exploration noise of ``log_std_init``.

The ``imitation`` library is not used: its last release (1.0.1) pins gymnasium ~0.29 and
stable-baselines3 ~2.2, older than this package's; the loss it would run is the few lines of
:func:`pretrain`.

Everything is seeded from the run's seed (the demonstrations' episodes, the noise, the
mini-batches), so a run's curve stays the same for the same seed.

Example:
    >>> from gripper.rl.demonstrations import collect_demonstrations      # doctest: +SKIP
    >>> demo = collect_demonstrations({"objects": ("block",), "action_mode": "synergy"},
    ...                               episodes=8, noise=0.3, seed=0)       # doctest: +SKIP
    >>> demo.obs.shape[0] == demo.steps                                    # doctest: +SKIP
    True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

# Seed offset of the demonstrations' episodes: far from the training chunks' hashed seeds and from
# the evaluation seeds (gripper.rl.config.EVAL_SEED), which they must not share.
DEMO_SEED = 2_000_000_000
BC_EPOCHS = 20          # passes over the demonstrations (the loss levels off by then)
BC_BATCH = 256
BC_LEARNING_RATE = 1e-3  # Adam; the ``imitation`` library's BC default


@dataclass(frozen=True)
class Demonstrations:
    """Transitions of the scripted grasp (arrays over steps, in the environment's order).

    ``obs`` and ``next_obs``: observations before and after the step (the final observation of an
    episode that ended); ``label``: the demonstrator's action; ``action``: the executed action
    (label plus noise, clipped); ``reward``; ``done`` (the episode ended at this step:
    terminated or truncated); ``terminated``; ``success``: per episode, held at some step.
    """

    obs: np.ndarray
    next_obs: np.ndarray
    label: np.ndarray
    action: np.ndarray
    reward: np.ndarray
    done: np.ndarray
    terminated: np.ndarray
    success: np.ndarray

    @property
    def steps(self) -> int:
        return len(self.obs)

    def returns(self, gamma: float) -> np.ndarray:
        """Discounted return from each step to its episode's end."""
        out = np.zeros(self.steps)
        g = 0.0
        for t in range(self.steps - 1, -1, -1):
            g = self.reward[t] + gamma * (0.0 if self.done[t] else g)
            out[t] = g
        return out


def collect_demonstrations(env_kwargs: dict[str, Any], episodes: int, noise: float, seed: int,
                           n_envs: int = 8) -> Demonstrations:
    """``episodes`` whole episodes of the scripted grasp with DART noise ``noise`` (standard
    deviation, in action units), in a native vector env of ``n_envs`` slots seeded from ``seed``.
    Transitions are stored episode by episode (each slot's episodes contiguous)."""
    import gymnasium as gym

    from gripper.envs.registration import ENV_ID
    from gripper.envs.scripted_grasp import ScriptedGrasp

    kw = dict(env_kwargs)
    max_steps = kw.pop("max_episode_steps", 300)
    venv = gym.make_vec(f"gripper:{ENV_ID}", num_envs=n_envs, vectorization_mode="vector_entry_point", nthread=1,
                        max_episode_steps=max_steps, **kw)
    expert = ScriptedGrasp(venv.config)  # type: ignore[attr-defined]
    rng = np.random.default_rng([seed, 7])
    per_slot: list[list[list]] = [[] for _ in range(n_envs)]  # each slot's finished episodes
    current: list[list] = [[] for _ in range(n_envs)]
    held = np.zeros(n_envs, dtype=bool)
    wins: list[bool] = []
    try:
        obs, _ = venv.reset(seed=DEMO_SEED + 1000 * seed)
        active = np.arange(n_envs) < episodes
        started = int(active.sum())  # episodes begun
        resetting = np.zeros(n_envs, dtype=bool)  # ended last step: this step resets the slot
        while active.any():
            label = expert(obs)
            act = np.clip(label + noise * rng.standard_normal(label.shape), -1.0, 1.0).astype(np.float32)
            nxt, rew, term, trunc, info = venv.step(act)
            succ = np.asarray(info.get("is_success", np.zeros(n_envs, dtype=bool)), dtype=bool)
            for i in np.flatnonzero(active):
                if resetting[i]:  # Gymnasium's NEXT_STEP autoreset: nxt[i] is a new episode's start
                    resetting[i] = False
                    continue
                current[i].append((obs[i], nxt[i], label[i], act[i], rew[i], term[i] or trunc[i], term[i]))
                held[i] |= succ[i]
                if term[i] or trunc[i]:
                    per_slot[i].append(current[i])
                    wins.append(bool(held[i]))
                    current[i], held[i], resetting[i] = [], False, True
                    if started < episodes:
                        started += 1
                    else:
                        active[i] = False
            obs = nxt
    finally:
        venv.close()
    rows = [t for slot in per_slot for ep in slot for t in ep]
    cols = list(zip(*rows, strict=True))
    return Demonstrations(obs=np.array(cols[0]), next_obs=np.array(cols[1]), label=np.array(cols[2]),
                          action=np.array(cols[3]), reward=np.array(cols[4], dtype=np.float64),
                          done=np.array(cols[5], dtype=bool), terminated=np.array(cols[6], dtype=bool),
                          success=np.array(wins))


def pretrain(model, demo: Demonstrations, seed: int, epochs: int = BC_EPOCHS) -> dict[str, float]:
    """Behaviour cloning of ``model`` (an SB3 PPO or SAC) on ``demo``, in place: the policy's mean
    action (SAC: its deterministic, squashed action) regressed on the labels; for PPO also the
    value on the discounted returns (the model's ``gamma``). Returns the last epoch's mean
    losses (``bc_action_mse``, and for PPO ``bc_value_mse``)."""
    import torch
    from stable_baselines3 import PPO

    ppo = isinstance(model, PPO)
    policy = model.policy
    gen = torch.Generator().manual_seed(int(seed))
    obs = torch.as_tensor(demo.obs, dtype=torch.float32)
    label = torch.as_tensor(demo.label, dtype=torch.float32)
    ret = torch.as_tensor(demo.returns(model.gamma), dtype=torch.float32)
    params = list(policy.parameters()) if ppo else list(policy.actor.parameters())
    opt = torch.optim.Adam(params, lr=BC_LEARNING_RATE)
    policy.set_training_mode(True)
    n = len(obs)
    losses: dict[str, float] = {}
    for _ in range(epochs):
        perm = torch.randperm(n, generator=gen)
        sums = np.zeros(2)
        for start in range(0, n, BC_BATCH):
            idx = perm[start:start + BC_BATCH]
            o = obs[idx]
            if ppo:
                mean = policy.get_distribution(o).distribution.mean
                value = policy.predict_values(o).squeeze(-1)
                a_loss = torch.mean((mean - label[idx]) ** 2)
                v_loss = torch.mean((value - ret[idx]) ** 2)
                loss = a_loss + v_loss
            else:
                a_loss = torch.mean((policy.actor(o, deterministic=True) - label[idx]) ** 2)
                v_loss = torch.zeros(())
                loss = a_loss
            opt.zero_grad()
            loss.backward()
            opt.step()
            sums += [float(a_loss.detach()) * len(idx), float(v_loss.detach()) * len(idx)]
        losses = {"bc_action_mse": sums[0] / n, **({"bc_value_mse": sums[1] / n} if ppo else {})}
    policy.set_training_mode(False)
    return losses


def fill_replay_buffer(model, demo: Demonstrations) -> int:
    """Put the demonstrations' transitions (the executed actions) into an off-policy model's
    replay buffer, ``n_envs`` at a time; return how many went in."""
    buf = model.replay_buffer
    k = buf.n_envs
    m = (demo.steps // k) * k
    for s in range(0, m, k):
        sl = slice(s, s + k)
        infos = [{"TimeLimit.truncated": bool(d and not t)} for d, t in
                 zip(demo.done[sl], demo.terminated[sl], strict=True)]
        buf.add(demo.obs[sl], demo.next_obs[sl], demo.action[sl], demo.reward[sl], demo.done[sl], infos)
    return m
