"""Gymnasium environment ``SoftGripperGrasp-v12``: grasp and lift one object with the soft gripper.

Registered when ``gripper`` is imported: ``gymnasium.make("gripper:SoftGripperGrasp-v12")``.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from gripper.core.arguments import check_instance
from gripper.core.params import GripperParams
from gripper.envs.config import EnvConfig
from gripper.envs.registration import ENV_ID
from gripper.envs.task import (
    BatchStepper,
    EpisodeState,
    SceneSet,
    evaluate,
    observation_divisor,
    observation_structure,
    observe,
    start_episode,
    unstable_result,
)

# "human" (MuJoCo's viewer window) is offered only where a display exists
RENDER_MODES = ["rgb_array", "depth_array"] + (
    ["human"] if os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY") else [])


# The environment's own arguments besides EnvConfig's fields: the design's fingers and
# calibration file (``params``, an EnvConfig field, also takes a parameter file), and the renderer's.
DESIGN_ARGUMENTS = ("calibration", "actuation")
RENDER_ARGUMENTS = {"render_mode": None, "width": 640, "height": 480, "camera": "front"}


def make_config(**kwargs: Any) -> EnvConfig:
    """The validated :class:`EnvConfig` of keyword arguments named as its fields (``objects`` may
    be "a,b"), plus ``params`` (a GripperParams or a parameter file), ``actuation`` (``"cable"``
    or ``"pneumatic"``: the fingers, overriding the parameters') and ``calibration``.

    Raises:
        ValueError: an unknown argument (naming the allowed ones) or a bad value.
    """
    allowed = [f.name for f in dataclasses.fields(EnvConfig)] + list(DESIGN_ARGUMENTS)
    unknown = sorted(set(kwargs) - set(allowed))
    if unknown:
        raise ValueError(f"{ENV_ID}: unknown argument {', '.join(unknown)}; allowed: "
                         f"{', '.join(allowed)}, {', '.join(RENDER_ARGUMENTS)}")
    kwargs = dict(kwargs)
    objects = kwargs.get("objects")
    if isinstance(objects, str):
        kwargs["objects"] = tuple(o.strip() for o in objects.split(",") if o.strip())
    elif objects is not None:
        if not isinstance(objects, list | tuple) or not all(isinstance(o, str) for o in objects):
            raise TypeError(f"objects: expected object names (a list, or 'a,b'), got {objects!r}")
        kwargs["objects"] = tuple(objects)
    params = kwargs.pop("params", None)
    if params is None:
        params = GripperParams()
    elif not isinstance(params, GripperParams):
        check_instance("params", params, (str, Path), optional=False)
        try:
            params = GripperParams.load(params)
        except ValueError as e:
            raise ValueError(f"params: {e}") from None
    actuation = kwargs.pop("actuation", None)
    if actuation is not None:  # the fingers: "cable" or "pneumatic" (GripperParams.actuation)
        params = params.replace(actuation=params.actuation.replace(kind=actuation)).validate()
    calibration = kwargs.pop("calibration", None)
    if calibration is not None:
        from gripper.calibration.calfile import apply_calibration
        params = apply_calibration(params, calibration)
    if kwargs.get("reward_weights") is None:
        kwargs.pop("reward_weights", None)
    else:
        kwargs["reward_weights"] = dict(kwargs["reward_weights"])
    return EnvConfig(params=params, **kwargs).validate()


def env_arguments(**kwargs) -> dict:
    """Split keyword arguments into the renderer's (with their defaults) and the validated
    ``config`` (:func:`make_config`)."""
    render = {k: kwargs.pop(k, default) for k, default in RENDER_ARGUMENTS.items()}
    return {**render, "config": make_config(**kwargs)}


def check_render_args(render_mode, width, height, camera) -> None:
    if render_mode is not None and render_mode not in RENDER_MODES:
        raise ValueError(f"render_mode: must be one of {RENDER_MODES} or None, got {render_mode!r}")
    from gripper.render.renderer import check_view
    check_view(width, height, camera)


def make_spaces(cfg: EnvConfig) -> tuple[dict, spaces.Box, spaces.Box]:
    """(observation structure, observation space, action space) of one environment."""
    structure = observation_structure(cfg)
    n_obs = sum(size for _, size, _ in structure.values())
    return (structure, spaces.Box(-np.inf, np.inf, (n_obs,), np.float64),
            spaces.Box(-1.0, 1.0, (cfg.action_size,), np.float32))


class SoftGripperGraspEnv(gym.Env):
    """Grasp one object with the soft gripper and lift it, as the grasp benchmark does
    (``gripper bench``): at least 8 cm, held for ``success_hold_s``, without slipping or
    damaging it. The fingers are cable-driven by default (``actuation="pneumatic"``: the
    pneumatic gripper's); the object is drawn from ``objects`` and placed with noise.

    **Actions**: ``Box(-1, 1, (n,), float32)``: one closing command per finger (one for all with
    ``action_mode="synergy"``), then the palm's lift (and its x and y with ``xy_actions``). By
    default each entry is a velocity that moves its actuator's set-point, which is observed, and
    0 holds it (``servo_control``, ``palm_control``). ``lift_action(height)``,
    ``command_action(command)`` and ``xy_action(offset)`` give the position-mode value for a palm
    height [m], a drive command (a servo's spool angle [rad], a regulator's pressure [Pa]) or a
    palm x/y offset [m].

    **Observations**: ``Box(-inf, inf, (107,), float64)`` for the default cable gripper (123 for
    the pneumatic one): hinge angles and velocities, the drive's state and set-points, the palm's
    height and set-point, the object's pose relative to the palm, pad and finger-object forces
    and what the drive's hardware reports, each part divided by its scale
    (``scale_observations``). The layout is ``observation_structure`` (name -> (start, size,
    unit)).

    **Reward**: dense (reach with open fingers, contact, lift, success, damage and action terms,
    each returned in ``info``) or sparse (``info["is_success"]``, the benchmark's held grasp).
    An episode ends when the object leaves the workspace or is damaged, or when the simulation
    goes unstable; it is truncated after 300 control steps.

    The tables, terms and rules: [Gymnasium environment](environment.md#action-space).

    ## Version history

    - v12: the dense reward is a ladder (issue 49). Every version:
      [version history](environment.md#version-history).

    Example:
        >>> import gymnasium as gym
        >>> env = gym.make("gripper:SoftGripperGrasp-v12", objects="block")   # doctest: +SKIP
        >>> obs, info = env.reset(seed=0)                                     # doctest: +SKIP
        >>> obs, r, term, trunc, info = env.step(env.action_space.sample())  # doctest: +SKIP
    """

    metadata = {"render_modes": RENDER_MODES, "render_fps": 50}

    def __init__(self, render_mode: str | None = None, width: int = 640, height: int = 480, camera: str = "front",
                 **kwargs: Any):
        self.config = make_config(**kwargs)
        check_render_args(render_mode, width, height, camera)
        # what rebuilds this environment (pickling, vector copies): the validated config's own
        # fields, so a file path given as params travels as the parameters it held
        self._init_kwargs = {**{f.name: getattr(self.config, f.name) for f in dataclasses.fields(EnvConfig)},
                             "render_mode": render_mode, "width": width, "height": height, "camera": camera}
        self.render_mode, self.width, self.height, self.camera = render_mode, width, height, camera
        self.metadata = {**self.metadata, "render_fps": int(round(1.0 / self.config.control_period))}
        self.observation_structure, self.observation_space, self.action_space = make_spaces(self.config)
        # observation = physical value / divisor (``scale_observations``); times it: SI units
        self.observation_divisor = observation_divisor(self.config)
        self._scenes = SceneSet(self.config)
        self._stepper = BatchStepper(nthread=0)
        self._ep: EpisodeState | None = None
        self._renderer = None
        self._viewer = None

    # --- gymnasium API ---------------------------------------------------------------------

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        self._ep = start_episode(self._scenes, self.np_random)
        obs = observe(self._ep, self._ep.data.sensordata) / self.observation_divisor
        self._ep.last_obs = obs
        return obs.copy(), {"object": self._ep.scene.obj.name, "is_success": False,
                            "placement": vars(self._ep.placement).copy()}

    def step(self, action):
        if self._ep is None:
            raise RuntimeError("step: call reset() first")
        action = check_action(action, self.action_space.shape)
        ep = self._ep
        ctrl = ep.scene.controls(action, ep.data.ctrl)
        sens, err = self._stepper.step([ep], [ctrl])[0]
        ep.steps += 1
        if err is not None:
            obs, reward, terminated, info = unstable_result(ep, err)
            return obs, reward, terminated, False, info
        raw = observe(ep, sens)
        obs = raw / self.observation_divisor
        ep.last_obs = obs
        reward, terminated, info = evaluate(ep, raw, sens, action, self.config, self.observation_structure)
        if self.render_mode == "human":
            self.render()
        return obs.copy(), reward, terminated, False, info

    def lift_action(self, palm_height: float) -> float:
        """Action value that sets the palm face ``palm_height`` above the floor [m]."""
        return self._scene_for_actions().lift_action(palm_height)

    def xy_action(self, offset: float) -> float:
        """Action value (x or y, with ``xy_actions``) that sets the palm ``offset`` from home [m]."""
        return self._scene_for_actions().xy_action(offset)

    def command_action(self, command: float) -> float:
        """Action value (a finger's, in position mode) that sets the drive's command to
        ``command``: a servo's spool angle [rad], a pneumatic regulator's pressure [Pa]."""
        return self._scene_for_actions().command_action(command)

    def servo_action(self, angle: float) -> float:
        """:meth:`command_action` under its earlier name (kept for existing callers)."""
        return self.command_action(angle)

    def _scene_for_actions(self):
        if self._ep is not None:
            return self._ep.scene
        raise RuntimeError("call reset() first")

    def render(self):
        if self.render_mode is None:
            gym.logger.warn("render: no render_mode was given at construction")
            return None
        if self._ep is None:
            raise RuntimeError("render: call reset() first")
        m, d = self._ep.scene.model, self._ep.data
        if self.render_mode == "human":
            from gripper.render.renderer import open_viewer
            if self._viewer is None or self._viewer.model is not m:
                if self._viewer is not None:
                    self._viewer.close()
                self._viewer = open_viewer(m, d)
            self._viewer.sync()
            return None
        from gripper.render.renderer import SceneRenderer
        if self._renderer is None or self._renderer.model is not m:
            if self._renderer is not None:
                self._renderer.close()
            self._renderer = SceneRenderer(m, width=self.width, height=self.height, camera=self.camera)
        return self._renderer.render(d, depth=self.render_mode == "depth_array")

    def close(self):
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
        if self._viewer is not None:
            self._viewer.close()
            self._viewer = None

    # --- pickling: rebuild from the constructor arguments, then the state -------------------

    def __getstate__(self):
        episode = None
        if self._ep is not None:
            from gripper.envs.task import state_vector
            ep = self._ep
            episode = dict(object=ep.scene.obj.name, placement=vars(ep.placement).copy(),
                           qstate=state_vector(ep), ctrl=ep.data.ctrl.copy(),
                           book={k: getattr(ep, k) for k in EPISODE_BOOKKEEPING})
        return {"kwargs": self._init_kwargs, "np_random": self._np_random, "episode": episode}

    def __setstate__(self, st):
        self.__init__(**st["kwargs"])
        self._np_random = st["np_random"]
        if st["episode"] is not None:
            self._ep = restore_episode(self._scenes, st["episode"])


EPISODE_BOOKKEEPING = ("start_pos", "hold_ref", "hold_steps", "peak_strain", "damaged", "last_obs", "steps",
                       "sensor_rng")


def restore_episode(scenes: SceneSet, st: dict) -> EpisodeState:
    """Rebuild an episode from its pickled form (object, placement, state, bookkeeping)."""
    import mujoco

    from gripper.envs.task import Scene, load_state
    from gripper.objects.scene_objects import Placement
    obj = next(o for o in scenes.objects if o.name == st["object"])  # any spec form: by its name
    place = Placement(**st["placement"])
    scene = Scene(scenes.cfg, obj, place) if obj.is_flex else scenes._rigid[obj.name]
    if not obj.is_flex:
        scenes.apply_placement(scene, place)
    ep = EpisodeState(scene=scene, data=mujoco.MjData(scene.model), placement=place,
                      start_pos=np.zeros(3), **{k: v for k, v in st["book"].items() if k != "start_pos"})
    ep.start_pos = st["book"]["start_pos"]
    load_state(ep, st["qstate"], st["ctrl"])
    return ep


def check_action(action, shape) -> np.ndarray:
    """The action as float64, or a clear error naming the argument."""
    try:
        a = np.asarray(action, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"action: expected numbers of shape {shape}, got {action!r}") from None
    if a.shape != tuple(shape):
        raise ValueError(f"action: expected shape {tuple(shape)}, got {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError("action: contains NaN or infinity")
    return a

