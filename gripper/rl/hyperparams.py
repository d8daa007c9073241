"""The baselines' hyper-parameters, with the reason for each one that is not SB3's default.

``normalize`` is not an SB3 argument: it wraps the environments in SB3's ``VecNormalize``
(running mean and variance of the observations, and for PPO of the returns), as the RL Baselines3
Zoo does for every MuJoCo task. The observation mixes newtons, metres and radians per second,
whose scales differ by four orders of magnitude.

Example:
    >>> from gripper.rl.hyperparams import hyperparams_for
    >>> hyperparams_for("ppo", {"n_epochs": 5})["n_epochs"]
    5
"""

from __future__ import annotations

import math
from typing import Any

PPO_HYPERPARAMS: dict[str, Any] = {
    "learning_rate": 3e-4,   # SB3 default
    # 256 steps x 8 envs = 2,048 per update (SB3's default n_steps 2048 would be 16,384 with 8
    # envs: 61 updates in 1M steps, too few)
    "n_steps": 256,
    "batch_size": 256,       # 8 minibatches per epoch
    "n_epochs": 10,          # SB3 default
    "gamma": 0.99,           # SB3 default: a 2 s horizon at the 20 ms control period
    "gae_lambda": 0.95,      # SB3 default
    "clip_range": 0.2,       # SB3 default
    # an entropy bonus (SB3's default is 0): without it the servo's exploration noise fell from
    # sigma 0.75 to 0.15-0.2 by 459k steps in two of three seeds, before they found the grasp
    "ent_coef": 0.01,
    "vf_coef": 0.5,          # SB3 default
    "max_grad_norm": 0.5,    # SB3 default
    "net_arch": [64, 64],    # SB3 default (separate policy and value networks, tanh)
    "use_sde": False,
    "sde_sample_freq": 16,
    "log_std_init": 0.0,     # SB3 default
    "ortho_init": True,      # SB3 default
    "normalize": False,      # VecNormalize off: the environment scales observations and rewards (v7)
    # Learning from demonstrations (gripper.rl.demo_regulariser; with --demos only): the weight
    # of the behaviour-cloning term in each update's loss, its decay per update, and the updates
    # at the start during which only the critic learns. 0: off (plain PPO after cloning)
    "bc_weight": 0.0,
    "bc_decay": 1.0,
    "critic_warmup": 0,
}

SAC_HYPERPARAMS: dict[str, Any] = {
    "learning_rate": 3e-4,   # SB3 default
    "buffer_size": 300_000,  # the run's last 300k transitions: 230 MB of float32 observations
    "learning_starts": 10_000,
    "batch_size": 256,       # SB3 default
    "tau": 0.005,            # SB3 default
    "gamma": 0.99,           # as PPO
    "train_freq": 1,         # one update per vector step (8 transitions) ...
    "gradient_steps": 1,     # ... of one gradient step: 1 per 8 transitions, for wall time
    "ent_coef": "auto",      # SB3 default: the entropy target is -dim(action)
    "net_arch": [256, 256],  # SB3 default for SAC
    "normalize": False,      # as PPO's (True: VecNormalize on observations only)
}

# TQC (sb3-contrib): SAC's values plus its own (sb3-contrib's defaults); with a goal-conditioned
# task both replay hindsight goals (HER, Andrychowicz et al., 2017: 4 goals per transition from
# the episode's future, the paper's best strategy)
TQC_HYPERPARAMS: dict[str, Any] = {
    **SAC_HYPERPARAMS,
    "top_quantiles_to_drop_per_net": 2,  # sb3-contrib default
    "n_quantiles": 25,       # sb3-contrib default
    "n_critics": 2,          # sb3-contrib default
}
HER_SAMPLED_GOALS = 4  # hindsight goals per real one (the paper's k = 4), strategy "future"

# The recommended recipe (``gripper train --recommended``; docs/environment.md, "Baselines"):
# PPO from 64 episodes of the scripted grasp with DART noise 0.2 (the demonstrator holds 16 of 16
# at that noise), cloned, then PPO with exploration noise matched to the demonstrations' (σ =
# e^-1.6 = 0.2), a critic warm-up of 4 updates (8,192 steps) and a behaviour-cloning term of
# weight 1 decaying by 1 % per update (0.28 after 128 updates: 262,144 steps)
RECOMMENDED: dict[str, Any] = {
    "algo": "ppo", "demo_episodes": 64, "demo_noise": 0.2,
    "hyperparams": {"log_std_init": -1.6, "bc_weight": 1.0, "bc_decay": 0.99, "critic_warmup": 4},
}

HYPERPARAMS = {"ppo": PPO_HYPERPARAMS, "sac": SAC_HYPERPARAMS, "tqc": TQC_HYPERPARAMS}


POLICY_KWARGS = ("net_arch", "log_std_init", "ortho_init", "n_quantiles", "n_critics")  # passed in policy_kwargs
NOT_SB3 = ("normalize", "bc_weight", "bc_decay", "critic_warmup")


def _check(name: str, value: Any, default: Any) -> None:
    if name == "log_std_init":
        ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
    elif isinstance(default, bool):
        ok = isinstance(value, bool)
    elif isinstance(default, int):
        ok = isinstance(value, int) and not isinstance(value, bool) and value >= 0
    elif isinstance(default, float):
        ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value) and value >= 0
    elif isinstance(default, list):
        ok = isinstance(value, list) and bool(value) and all(isinstance(v, int) and v > 0 for v in value)
    else:  # ent_coef: "auto" or a number
        ok = value == "auto" or (isinstance(value, int | float) and not isinstance(value, bool) and value > 0)
    if not ok:
        raise ValueError(f"hyperparams.{name}: expected a value like {default!r}, got {value!r}")


def hyperparams_for(algo: str, overrides: dict | None = None) -> dict[str, Any]:
    """``algo``'s hyper-parameters with ``overrides`` applied (each checked against its kind)."""
    base = HYPERPARAMS[algo]
    out = dict(base)
    for k, v in (overrides or {}).items():
        if k not in base:
            raise ValueError(f"hyperparams.{k}: unknown for {algo}; allowed: {', '.join(base)}")
        _check(k, v, base[k])
        out[k] = v
    return out
