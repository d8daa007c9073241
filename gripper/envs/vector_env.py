"""Native vector environment of ``SoftGripperGrasp-v12``: N simulations stepped together by one
``mujoco.rollout`` call per control step, on MuJoCo's own thread pool.

Created by ``gymnasium.make_vec("gripper:SoftGripperGrasp-v12", num_envs=N,
vectorization_mode="vector_entry_point")``. Slot ``i`` of a vector environment reset with seed
``s`` runs exactly the episode of a single environment reset with seed ``s + i`` (Gymnasium's
convention for seeded vector resets), observation for observation.

Autoreset follows Gymnasium's default ``NEXT_STEP`` mode: the step after a slot's episode ended
resets that slot (its action is ignored, its reward is 0, terminated and truncated are False)
and returns the new episode's first observation.

Example:
    >>> import gymnasium as gym
    >>> envs = gym.make_vec("gripper:SoftGripperGrasp-v12", num_envs=4,
    ...                     vectorization_mode="vector_entry_point")          # doctest: +SKIP
    >>> obs, info = envs.reset(seed=0)                                       # doctest: +SKIP
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from gripper.envs.grasp_env import RENDER_MODES, check_action, check_render_args, env_arguments, make_spaces
from gripper.envs.registration import MAX_EPISODE_STEPS
from gripper.envs.task import (
    BatchStepper,
    SceneSet,
    evaluate,
    observation_divisor,
    observe,
    start_episode,
    unstable_result,
)


class SoftGripperGraspVectorEnv(VectorEnv):
    """``num_envs`` copies of :class:`gripper.envs.grasp_env.SoftGripperGraspEnv` stepped as one batch.

    Takes the single environment's keyword arguments plus ``num_envs``, ``max_episode_steps``
    (truncation, as the single environment's TimeLimit) and ``nthread`` (MuJoCo threads; default
    the number of CPU cores, at most ``num_envs``). ``render()`` returns slot 0's image.
    """

    metadata = {"render_modes": RENDER_MODES, "render_fps": 50, "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, max_episode_steps: int | None = MAX_EPISODE_STEPS, nthread: int | None = None,
                 **env_kwargs: Any):
        if not isinstance(num_envs, int) or num_envs < 1:
            raise ValueError(f"num_envs: must be an integer >= 1, got {num_envs!r}")
        if max_episode_steps is not None and (not isinstance(max_episode_steps, int) or max_episode_steps < 1):
            raise ValueError(f"max_episode_steps: must be an integer >= 1 or None, got {max_episode_steps!r}")
        args = env_arguments(**env_kwargs)  # the single env's arguments and defaults
        self.config = args["config"]
        render_mode, width, height, camera = (args[k] for k in ("render_mode", "width", "height", "camera"))
        check_render_args(render_mode, width, height, camera)
        self.num_envs = num_envs
        self.max_episode_steps = max_episode_steps
        self.render_mode, self.width, self.height, self.camera = render_mode, width, height, camera
        self.metadata = {**self.metadata, "render_fps": int(round(1.0 / self.config.control_period))}
        self.observation_structure, self.single_observation_space, self.single_action_space = (
            make_spaces(self.config))
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.observation_divisor = observation_divisor(self.config)  # as the single env's
        self._obs_shape: tuple[int, ...] = self.single_observation_space.shape or ()
        self.action_space = batch_space(self.single_action_space, num_envs)
        # one scene set per slot: rigid scenes carry per-episode mass and friction
        self._scenes = [SceneSet(self.config) for _ in range(num_envs)]
        n = nthread if nthread is not None else min(num_envs, os.cpu_count() or 1)
        self._stepper = BatchStepper(nthread=n if n > 1 else 0)
        self._eps: list = [None] * num_envs
        self._rngs: list[np.random.Generator | None] = [None] * num_envs
        self._autoreset = np.zeros(num_envs, dtype=bool)
        self._renderer = None

    def reset(self, *, seed: int | list[int | None] | None = None, options: dict | None = None):
        if seed is None or isinstance(seed, int):
            seeds = [None if seed is None else seed + i for i in range(self.num_envs)]
        else:
            if len(seed) != self.num_envs:
                raise ValueError(f"seed: expected {self.num_envs} seeds, got {len(seed)}")
            seeds = list(seed)
        mask = None if options is None else options.get("reset_mask")
        obs = np.zeros((self.num_envs, *self._obs_shape))
        infos: dict = {}
        for i in range(self.num_envs):
            if mask is not None and not mask[i]:
                obs[i] = self._eps[i].last_obs
                continue
            if seeds[i] is not None or self._rngs[i] is None:
                self._rngs[i], _ = seeding.np_random(seeds[i])
            obs[i], info = self._reset_slot(i)
            infos = self._add_info(infos, info, i)
        self._autoreset[:] = False if mask is None else self._autoreset & ~np.asarray(mask)
        return obs, infos

    def _reset_slot(self, i: int):
        rng = self._rngs[i]
        assert rng is not None, "reset seeds every slot's generator first"
        ep = start_episode(self._scenes[i], rng)
        ep.last_obs = observe(ep, ep.data.sensordata) / self.observation_divisor
        self._eps[i] = ep
        return ep.last_obs.copy(), {"object": ep.scene.obj.name, "is_success": False,
                                    "placement": vars(ep.placement).copy()}

    def step(self, actions):
        actions = check_action(actions, self.action_space.shape)
        if any(ep is None for ep in self._eps):
            raise RuntimeError("step: call reset() first")
        n = self.num_envs
        obs = np.zeros((n, *self._obs_shape))
        rewards = np.zeros(n)
        terminated = np.zeros(n, dtype=bool)
        truncated = np.zeros(n, dtype=bool)
        per_env: list = [None] * n
        live = [i for i in range(n) if not self._autoreset[i]]
        for i in range(n):
            if self._autoreset[i]:
                obs[i], per_env[i] = self._reset_slot(i)
        results = self._stepper.step([self._eps[i] for i in live],
                                     [self._eps[i].scene.controls(actions[i], self._eps[i].data.ctrl) for i in live])
        for i, (sens, err) in zip(live, results, strict=True):
            ep = self._eps[i]
            ep.steps += 1
            if err is not None:
                obs[i], rewards[i], terminated[i], info = unstable_result(ep, err)
            else:
                raw = observe(ep, sens)
                obs[i] = raw / self.observation_divisor
                ep.last_obs = obs[i].copy()
                rewards[i], terminated[i], info = evaluate(ep, raw, sens, actions[i], self.config,
                                                           self.observation_structure)
            truncated[i] = (not terminated[i] and self.max_episode_steps is not None
                            and ep.steps >= self.max_episode_steps)
            per_env[i] = info
        self._autoreset = terminated | truncated
        return obs, rewards, terminated, truncated, self._merge_infos(per_env)

    def _merge_infos(self, per_env: list) -> dict:
        """Gymnasium's vector info layout (``info[k]`` array, ``info["_k"]`` mask), built one key
        at a time instead of one env at a time; dict values go through ``_add_info``."""
        n = self.num_envs
        out: dict = {}
        keys = dict.fromkeys(k for d in per_env if d for k in d)
        for k in keys:
            mask = np.array([d is not None and k in d for d in per_env])
            vals = [d[k] for d, m in zip(per_env, mask, strict=True) if m]
            if isinstance(vals[0], dict):
                for i, d in enumerate(per_env):
                    if d is not None and k in d:
                        out = self._add_info(out, {k: d[k]}, i)
                continue
            dtype = bool if isinstance(vals[0], bool | np.bool_) else (
                np.float64 if isinstance(vals[0], int | float | np.number) else object)
            arr = np.zeros(n, dtype=dtype) if dtype is not object else np.full(n, None, dtype=object)
            arr[mask] = vals
            out[k], out["_" + k] = arr, mask
        return out

    def render(self):
        if self.render_mode is None or self._eps[0] is None:
            return None
        from gripper.render.renderer import SceneRenderer
        ep = self._eps[0]
        if self._renderer is None or self._renderer.model is not ep.scene.model:
            if self._renderer is not None:
                self._renderer.close()
            self._renderer = SceneRenderer(ep.scene.model, width=self.width, height=self.height,
                                           camera=self.camera)
        return self._renderer.render(ep.data, depth=self.render_mode == "depth_array")

    def close_extras(self, **kwargs):
        self._stepper.close()
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
