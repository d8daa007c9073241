"""Goal-conditioned variant ``SoftGripperGraspGoal-v12``: lift the object to a target point,
with the dict observation and ``compute_reward`` of Gymnasium-Robotics' Fetch tasks and
panda-gym, which hindsight experience replay (SB3's ``HerReplayBuffer``) needs.

The task and its physics are ``SoftGripperGrasp-v12``'s (same arguments, actions, physics,
termination and truncation). What differs:

- **Observation**: ``Dict(observation=Box(107), achieved_goal=Box(3), desired_goal=Box(3))``.
  ``observation`` is the base environment's; ``achieved_goal`` is the object's position (its
  reference point, world frame, metres) and ``desired_goal`` the lift target: the object's
  start position raised by ``h ~ U(0.04, 0.10) m``, drawn from the episode's generator after the
  object and its placement (so slot ``i`` of a vector env reset with seed ``s`` runs the episode
  of a single env reset with ``s + i``, goal included). Both goals are divided by the object
  position's scale (0.1 m) when ``scale_observations`` is on, as the base observation's parts are.
- **Reward** (``compute_reward(achieved_goal, desired_goal, info)``, vectorised over leading
  axes, as HER calls it): ``reward_type="sparse"`` (the default here, as Fetch's) gives
  ``-(d > 0.02 m)``, ``"dense"`` gives ``-d`` [m], ``d`` the distance between the goals. The base
  environment's dense terms are not paid.
- **Success**: ``info["is_success"]`` is ``d <= 0.02 m`` at that step; an evaluation counts the
  episode's last step (Fetch's rule). The base environment's held grasp is ``info["grasp_held"]``.

Why this goal: a lift target is what the grasp benchmark asks of a grasp (8 cm, the base task's
success height, lies inside the range), and a point target lets HER relabel every transition
with a goal the object actually reached. The range starts at 4 cm so that a goal is never met by
leaving the object on the floor (0.02 m tolerance).

Example:
    >>> import gymnasium as gym
    >>> env = gym.make("gripper:SoftGripperGraspGoal-v12", objects="block")    # doctest: +SKIP
    >>> obs, info = env.reset(seed=0)                                          # doctest: +SKIP
    >>> sorted(obs)                                                            # doctest: +SKIP
    ['achieved_goal', 'desired_goal', 'observation']
    >>> env.unwrapped.compute_reward(obs["achieved_goal"], obs["desired_goal"], {})  # doctest: +SKIP
    -1.0
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces
from gymnasium.vector.utils import batch_space

from gripper.envs.config import OBSERVATION_SCALES, EnvConfig
from gripper.envs.grasp_env import SoftGripperGraspEnv
from gripper.envs.vector_env import SoftGripperGraspVectorEnv

LIFT_TARGET = (0.04, 0.10)  # m: the goal's rise above the object's start, drawn uniformly
GOAL_TOLERANCE = 0.02       # m: the goal is met within this distance (Fetch's is 0.05 m)


def goal_scale(cfg: EnvConfig) -> float:
    """What goals are divided by: the object position's scale with ``scale_observations``."""
    return OBSERVATION_SCALES["object_pos_rel_palm"][0] if cfg.scale_observations else 1.0


def goal_space(cfg: EnvConfig, observation: spaces.Space) -> spaces.Dict:
    goal = spaces.Box(-np.inf, np.inf, (3,), np.float64)
    return spaces.Dict({"observation": observation, "achieved_goal": goal, "desired_goal": goal})


def goal_distance(achieved, desired, cfg: EnvConfig) -> np.ndarray:
    """Distance [m] between scaled goals (any leading shape)."""
    return np.linalg.norm(np.asarray(achieved, dtype=np.float64) - np.asarray(desired, dtype=np.float64),
                          axis=-1) * goal_scale(cfg)


def goal_reward(achieved: np.ndarray, desired: np.ndarray, cfg: EnvConfig) -> np.ndarray:
    """The reward of reaching ``achieved`` for ``desired`` (any leading shape, scaled goals)."""
    d = goal_distance(achieved, desired, cfg)
    if cfg.reward_type == "sparse":
        return -(d > GOAL_TOLERANCE).astype(np.float64)
    return -d


def draw_goal(rng: np.random.Generator, start: np.ndarray) -> np.ndarray:
    """The lift target [m, world frame] of an object starting at ``start``."""
    return np.asarray(start, dtype=np.float64) + np.array([0.0, 0.0, rng.uniform(*LIFT_TARGET)])


def object_position(ep) -> np.ndarray:
    return ep.scene.probe.object_pos(ep.data)


class SoftGripperGraspGoalEnv(SoftGripperGraspEnv):
    """``SoftGripperGrasp`` with a lift target: see the module's docstring. Takes the base
    environment's arguments; ``reward_type`` defaults to ``"sparse"``."""

    def __init__(self, **kwargs: Any):
        kwargs.setdefault("reward_type", "sparse")
        super().__init__(**kwargs)
        self.observation_space = goal_space(self.config, self.observation_space)
        self._scale = goal_scale(self.config)
        self._goal = np.zeros(3)

    def compute_reward(self, achieved_goal, desired_goal, info) -> np.ndarray | float:
        r = goal_reward(achieved_goal, desired_goal, self.config)
        return float(r) if np.ndim(r) == 0 else r

    def _dict(self, obs: np.ndarray) -> dict[str, np.ndarray]:
        assert self._ep is not None
        return {"observation": obs, "achieved_goal": object_position(self._ep) / self._scale,
                "desired_goal": self._goal / self._scale}

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        obs, info = super().reset(seed=seed, options=options)
        assert self._ep is not None
        self._goal = draw_goal(self.np_random, self._ep.start_pos)
        return self._dict(obs), info

    def step(self, action):
        obs, _, terminated, truncated, info = super().step(action)
        out = self._dict(obs)
        info = {**info, "grasp_held": info["is_success"]}
        if info.get("unstable"):
            return out, 0.0, terminated, truncated, info
        reward = float(self.compute_reward(out["achieved_goal"], out["desired_goal"], info))
        info["is_success"] = bool(goal_distance(out["achieved_goal"], out["desired_goal"], self.config)
                                  <= GOAL_TOLERANCE)
        return out, reward, terminated, truncated, info

    def __getstate__(self):
        return {**super().__getstate__(), "goal": self._goal.copy()}

    def __setstate__(self, st):
        super().__setstate__(st)
        self._goal = st["goal"]


class SoftGripperGraspGoalVectorEnv(SoftGripperGraspVectorEnv):
    """``num_envs`` goal-conditioned environments stepped as one batch (the native vector env's
    arguments and autoreset; ``compute_reward`` as the single env's)."""

    def __init__(self, **kwargs: Any):
        kwargs.setdefault("reward_type", "sparse")
        super().__init__(**kwargs)
        self.single_observation_space = goal_space(self.config, self.single_observation_space)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self._scale = goal_scale(self.config)
        self._goals = np.zeros((self.num_envs, 3))

    def compute_reward(self, achieved_goal, desired_goal, info) -> np.ndarray:
        return goal_reward(achieved_goal, desired_goal, self.config)

    def _reset_slot(self, i: int):
        obs, info = super()._reset_slot(i)
        rng = self._rngs[i]
        assert rng is not None
        self._goals[i] = draw_goal(rng, self._eps[i].start_pos)
        return obs, info

    def _dict(self, obs: np.ndarray) -> dict[str, np.ndarray]:
        achieved = np.array([object_position(ep) for ep in self._eps]) / self._scale
        return {"observation": obs, "achieved_goal": achieved, "desired_goal": self._goals / self._scale}

    def reset(self, *, seed=None, options=None):
        obs, info = super().reset(seed=seed, options=options)
        return self._dict(obs), info

    def step(self, actions):
        resetting = self._autoreset.copy()
        obs, _, terminated, truncated, info = super().step(actions)
        out = self._dict(obs)
        d = goal_distance(out["achieved_goal"], out["desired_goal"], self.config)
        unstable = np.asarray(info.get("unstable", np.zeros(self.num_envs, dtype=bool)), dtype=bool)
        live = ~resetting & ~unstable
        rewards = np.where(live, self.compute_reward(out["achieved_goal"], out["desired_goal"], info), 0.0)
        held = np.asarray(info.get("is_success", np.zeros(self.num_envs, dtype=bool)), dtype=bool)
        info["grasp_held"], info["_grasp_held"] = held, ~resetting
        info["is_success"] = live & (d <= GOAL_TOLERANCE)
        info["_is_success"] = np.ones(self.num_envs, dtype=bool)
        return out, rewards, terminated, truncated, info
