"""One training run, validated: algorithm, task variant, budget, seed and evaluation.

Example:
    >>> from gripper.rl.config import TrainConfig
    >>> TrainConfig(algo="ppo", objects=("block",), steps=100_000).validate().env_kwargs()["objects"]
    ('block',)
    >>> TrainConfig(algo="dqn").validate()
    Traceback (most recent call last):
    ...
    ValueError: algo: must be one of ppo, sac, tqc, got 'dqn'
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field, fields
from typing import Any

from gripper.core.fields import Validated
from gripper.envs.registration import MAX_EPISODE_STEPS

ALGOS = ("ppo", "sac", "tqc")
# First seed of the evaluation episodes. Each training chunk seeds its envs' generators with a
# hash of (seed, chunk) in [0, 2^31) (slot i: hash + i) and draws every later episode from them,
# so a run of 16 chunks x 8 envs shares one of 50 evaluation seeds with probability ~3e-6.
EVAL_SEED = 1_000_000


@dataclass(frozen=True)
class TrainConfig(Validated):
    """A training run of ``SoftGripperGrasp`` with Stable-Baselines3.

    Attributes:
        algo: ``"ppo"``, ``"sac"`` or ``"tqc"`` (sb3-contrib's truncated quantile critics).
        goal_conditioned: train on ``SoftGripperGraspGoal`` (dict observations, a lift target);
            SAC and TQC then replay hindsight goals (SB3's ``HerReplayBuffer``).
        objects: objects sampled per episode (library names).
        action_mode: ``"synergy"`` (one servo command and the lift) or ``"fingers"``.
        xy_actions: add the palm's x/y velocity actions.
        steps: environment steps of the run (all envs together).
        seed: seeds the network, the algorithm's noise and the training episodes.
        n_envs: environments stepped together (the native vector env).
        chunk_steps: steps between evaluations and checkpoints. Training runs chunk by chunk;
            each chunk starts from a seeded reset of the envs and re-seeded generators, so a run
            resumed from a checkpoint is bitwise the run that never stopped. PPO rounds it up to
            a whole number of rollouts (``n_steps × n_envs``).
        eval_episodes: deterministic-policy episodes per evaluation, seeds from ``EVAL_SEED``.
        max_episode_steps: truncation (control steps of 20 ms).
        demo_episodes: episodes of the scripted grasp to learn from before reinforcement
            learning (behaviour cloning; SAC also keeps them in its replay buffer;
            :mod:`gripper.rl.demonstrations`); 0: none. Their steps count in ``demo_steps``.
        demo_noise: DART noise on the demonstrations' executed actions (standard deviation in
            action units; the labels stay the demonstrator's).
        hyperparams: overrides of :mod:`gripper.rl.hyperparams`'s values for ``algo``.
        reward_weights: overrides of the environment's dense reward weights (its
            ``reward_weights``; none for the baselines).
    """

    algo: str = "ppo"
    goal_conditioned: bool = False
    # The task variant: the environment's own arguments (each declared, with its allowed values,
    # in gripper.envs.config.EnvConfig, which validates them here). The baselines' task closes
    # all fingers with one command (the synergy), where a bare environment gives each its own.
    objects: tuple[str, ...] = ("block", "cylinder")
    action_mode: str = "synergy"
    xy_actions: bool = False
    steps: int = 1_000_000
    seed: int = 0
    n_envs: int = 8
    chunk_steps: int = 65_536
    eval_episodes: int = 50
    max_episode_steps: int = MAX_EPISODE_STEPS
    demo_episodes: int = 0
    demo_noise: float = 0.3
    hyperparams: dict = field(default_factory=dict)
    reward_weights: dict = field(default_factory=dict)

    def validate(self) -> TrainConfig:
        if self.algo not in ALGOS:
            raise ValueError(f"algo: must be one of {', '.join(ALGOS)}, got {self.algo!r}")
        if isinstance(self.objects, str) or not self.objects or not all(isinstance(o, str) for o in self.objects):
            raise ValueError(f"objects: expected a non-empty list of object names, got {self.objects!r}")
        from gripper.envs.config import EnvConfig

        # the task variant's arguments, checked where they are declared
        EnvConfig(objects=tuple(self.objects), action_mode=self.action_mode, xy_actions=self.xy_actions,
                  reward_weights=dict(self.reward_weights)).validate()
        if not isinstance(self.goal_conditioned, bool):
            raise ValueError(f"goal_conditioned: must be true or false, got {self.goal_conditioned!r}")
        if self.goal_conditioned and self.demo_episodes:
            raise ValueError("demo_episodes: the goal-conditioned task learns without demonstrations "
                             "(hindsight goals instead); give 0")
        for name, lo in (("steps", 1), ("seed", 0), ("n_envs", 1), ("chunk_steps", 1), ("eval_episodes", 1),
                         ("max_episode_steps", 1)):
            v = getattr(self, name)
            if not isinstance(v, int) or isinstance(v, bool) or v < lo:
                raise ValueError(f"{name}: must be an integer >= {lo}, got {v!r}")
        if not isinstance(self.demo_episodes, int) or isinstance(self.demo_episodes, bool) or not (
                0 <= self.demo_episodes <= 10_000):
            raise ValueError(f"demo_episodes: must be an integer in [0, 10000], got {self.demo_episodes!r}")
        if (isinstance(self.demo_noise, bool) or not isinstance(self.demo_noise, int | float)
                or not 0 <= self.demo_noise <= 1):
            raise ValueError(f"demo_noise: must be a number in [0, 1], got {self.demo_noise!r}")
        if self.n_envs > 64 or self.eval_episodes > 1000:
            raise ValueError("n_envs: at most 64; eval_episodes: at most 1000")
        from gripper.rl.hyperparams import hyperparams_for

        hp = hyperparams_for(self.algo, self.hyperparams)  # raises on an unknown or bad override
        if not self.demo_episodes and (hp.get("bc_weight", 0.0) > 0 or hp.get("critic_warmup", 0) > 0):
            raise ValueError("hyperparams.bc_weight, hyperparams.critic_warmup: need demonstrations "
                             "(demo_episodes >= 1)")
        if hp.get("bc_decay", 1.0) > 1.0:
            raise ValueError(f"hyperparams.bc_decay: must be in [0, 1], got {hp['bc_decay']!r}")
        if self.demo_episodes and hp["normalize"]:
            raise ValueError("demo_episodes: behaviour cloning needs hyperparams.normalize = false "
                             "(the environment scales its observations itself)")
        return self

    def env_id(self) -> str:
        """The registered environment this run trains on."""
        from gripper.envs.registration import ENV_ID, GOAL_ENV_ID
        return GOAL_ENV_ID if self.goal_conditioned else ENV_ID

    def env_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of ``SoftGripperGrasp`` for this task variant."""
        return {"objects": tuple(self.objects), "action_mode": self.action_mode, "xy_actions": self.xy_actions,
                "max_episode_steps": self.max_episode_steps, "reward_weights": dict(self.reward_weights)}

    def to_json(self) -> dict:
        d = asdict(self)
        d["objects"] = list(self.objects)
        return d

    @classmethod
    def from_json(cls, d: dict) -> TrainConfig:
        known = {f.name for f in fields(cls)}
        unknown = set(d) - known
        if unknown:
            raise ValueError(f"train config: unknown fields {sorted(unknown)}")
        d = dict(d)
        if "objects" in d:
            d["objects"] = tuple(d["objects"])
        return cls(**d).validate()

    def differences(self, other: TrainConfig) -> list[str]:
        """Names of the fields whose values differ (for a resume that must match)."""
        a, b = self.to_json(), other.to_json()
        return [k for k in a if json.dumps(a[k], sort_keys=True) != json.dumps(b[k], sort_keys=True)]

