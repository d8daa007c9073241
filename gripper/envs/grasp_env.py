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
    """Grasp one object with the four-finger, cable-driven soft gripper and lift it.

    ## Description

    A palm on a vertical lift axis (optionally x/y) carries four fingers; each finger is a chain
    of six silicone elements (the first fixed to the palm) joined at five hinges with torsion
    springs, bent by a cable that a hobby servo (MuJoCo ``dcmotor`` with position input, PD,
    voltage clamp and slew limit) reels in. One object from ``objects`` stands on the floor
    under the palm, offset by up to ``pose_noise`` in x and y (and turned at random where its
    shape is not symmetric). The task: close the fingers on it and lift it at least 8 cm
    without slipping or damaging it, as in the grasp benchmark (``gripper bench``).

    ## Action space

    ``Box(-1, 1, (n,), float32)``. By default every entry is a velocity: it moves its
    actuator's set-point, which is observed, and 0 holds it (``servo_control`` and
    ``palm_control``, ``"velocity"`` or ``"position"``):

    | action_mode | index | actuator | -1 | +1 | unit |
    |---|---|---|---|---|---|
    | fingers | 0-3 | servo of finger k (cable reeled in) | open at the slew rate | close at the slew rate | rad/s |
    | fingers | 4 | lift: palm-face height | down at palm_speed | up at palm_speed | m/s |
    | synergy | 0 | all four servos together | open at the slew rate | close at the slew rate | rad/s |
    | synergy | 1 | lift: palm-face height | down at palm_speed | up at palm_speed | m/s |
    | either, xy_actions | last 2 | palm x and y | -palm_speed | +palm_speed | m/s |

    ``"velocity"``: an entry moves its set-point by ``action × speed × control period``, kept in
    its range. Servo: the spool angle in [0, servo travel π], at the servo's slew rate (its
    no-load speed, 7.48 rad/s: 0.15 rad a step); palm: the palm-face height from fingertips
    4 mm above the floor up to home (0.25 m), x and y within ±0.02 m, at ``palm_speed`` (0.10
    m/s: 2 mm a step). ``"position"``: the entry is the set-point itself, -1 and +1 being the
    ends of those ranges (v3's actions). The set-points are observed (``servo_setpoint``,
    ``palm_setpoint``), so the state stays Markov.

    ``env.unwrapped.lift_action(height)``, ``servo_action(angle)`` and ``xy_action(offset)`` give
    the position-mode action value for a palm height [m], a spool angle [rad] or a palm x/y
    offset [m].
    Within a control period the palm set-points ramp linearly from the previous value to the new
    one (first-order hold, as a stage's trajectory generator; a step would jerk the stiff stage),
    while the servo set-points are held (zero-order hold, as a hobby servo's 50 Hz PWM command).
    The servos slew their set-point at the contraction speed (the servo's no-load speed), so a
    jump in a position action is followed at the speed the hardware allows.

    Why velocities: PPO and SAC explore with Gaussian action noise, σ ≈ 1 at the start. On a
    position set-point that noise moves the palm by centimetres every 20 ms and shakes any grasp
    apart, and an untrained policy (action ≈ 0) descends with the fingers half closed, which
    lands them on the object instead of around it; with velocities the noise is a slow random
    walk from the starting state (palm still, fingers open) (``docs/environment.md``).

    ## Observation space

    ``Box(-inf, inf, (107,), float64)`` with the default four fingers of six elements; the layout
    is ``env.observation_structure`` (name -> (start, size, unit)):

    | part | indices | size | unit |
    |---|---|---|---|
    | hinge_angle | 0-19 | 20 | rad |
    | hinge_velocity | 20-39 | 20 | rad/s |
    | cable_shortening | 40-43 | 4 | m |
    | cable_tension | 44-47 | 4 | N |
    | servo_angle | 48-51 | 4 | rad |
    | servo_setpoint | 52-55 | 4 | rad |
    | palm_height | 56-56 | 1 | m |
    | palm_setpoint | 57-59 | 3 | m |
    | object_pos_rel_palm | 60-62 | 3 | m |
    | object_quat | 63-66 | 4 | - |
    | pad_force | 67-90 | 24 | N |
    | finger_object_force | 91-94 | 4 | N |
    | sensed_servo_position | 95-98 | 4 | rad |
    | sensed_servo_current | 99-102 | 4 | A |
    | sensed_spool_tension | 103-106 | 4 | N |

    The ``sensed_*`` entries are what the servos report (:mod:`gripper.drives.cable.sensing`: present
    position in encoder counts, present current in 2.69 mA units, a spool load cell, each with
    its noise, drawn from the episode's seed).

    Hinge angles and velocities are finger-major (finger 0 hinges 2-6, then finger 1, ...).
    Cable shortening is the cable reeled onto the spool; tension is the cable's limit force;
    the palm height is the palm face above the floor; the palm set-point is the stages' current
    set-point (x and y from home, 0 without x/y stages; z as the palm-face height); the object
    position is its reference point (body origin, the bag's contents, or a flex's vertex
    centroid) relative to the palm centre; its orientation is a unit quaternion (identity for
    balloon and paper box, whose flex has no single frame); pad forces are the touch sensors of
    each element's pad (the inner faces' tooth tops), finger-major; the finger-object force is
    each finger's total normal contact force on the object over all its element faces (as the
    benchmark's force records; in the fingers' curled power grasp the object rests on the
    distal elements' hinge edges, which no pad covers). Forces (tension, pads) are the sensor values of the last
    physics step of the control period; everything else is the state at its end.

    ## Rewards

    ``reward_type="sparse"``: 1 at every step where the grasp counts as held (``is_success``),
    else 0. ``"dense"``: the sum of these terms, each returned in ``info`` (weights in
    ``reward_weights``, defaults in brackets):

    - ``reward_reach`` = w [0.1] × (1 − tanh(d / 0.05 m)) × openness, d the distance from the
      grasp point (mid-finger on the palm axis) to the object [m], openness 1 − the servos' mean
      set-point over their travel (1 open, 0 closed): coming close pays only with open fingers;
    - ``reward_contact`` = w [0.2] × (1 − tanh(d / 0.05 m)) × fraction of fingers pressing on
      the object (> 0.05 N), counted only when two opposing fingers press (azimuths at least
      120° apart): a grip around the object, not fingertips on its top;
    - ``reward_lift`` = w [0.2] × clip(object rise / 0.08 m, 0, 1);
    - ``reward_success`` = w [0.6] × is_success;
    - ``reward_damage`` = -w [1.25], once, when the object becomes damaged;
    - ``reward_action`` = -w [0.00125] × |action|².

    ``info["is_success"]`` is true once the object has been at least ``success_height`` (0.08 m)
    above its start, without slipping ``max_slip`` (20 mm) relative to the palm, for
    ``success_hold_s`` (1 s), and is not damaged: the grasp benchmark's definition of a held
    grasp (``gripper bench``), read at every control step.

    The weights make a ladder (``docs/environment.md``, "The reward ladder": the returns of
    idle, hovering, touching and holding policies, ``gripper.envs.reference_policies``): over
    300 steps a hand closed in the air earns about 0, one hovering open about 15, one gripping
    without lifting about 45 and a held grasp about 170. A held step at the grasp point pays 1
    (contact + lift + success).

    Every dense term but the penalties is ≥ 0, and success does not end the episode
    (``terminate_on_success=False``): each held step keeps paying. Ending it on success would
    make the dense reward teach the agent to hover just below the success height, since a held
    grasp would forfeit the lift reward of every remaining step (``docs/environment.md``).

    ## Starting state

    The palm at ``object height + finger length + 10 mm`` above the floor, fingers straight and
    servos at zero, the object standing on the floor (1 mm drop) at the sampled offset. The
    object is drawn uniformly from ``objects`` with the environment's generator.

    ## Episode end

    Terminated when the object leaves the workspace (more than 0.15 m from the axis, or below the
    floor), when it is damaged (its library criterion: the fingers' total contact force on a
    rigid part over its limit, read at every control step as the benchmark reads it; membrane or
    film strain for balloon and bag; for the paper box any plastic crease, stricter than the
    benchmark's spring-back dent), on success if ``terminate_on_success``, or
    when the simulation goes unstable (MuJoCo warning or non-finite state: ``info["unstable"]``
    and ``info["error"]``, reward 0, the last finite observation). Truncated after
    ``max_episode_steps`` (300 control steps, 6 s, by registration).

    ## Arguments

    ``gymnasium.make("gripper:SoftGripperGrasp-v12", **kwargs)``: the fields of
    :class:`gripper.envs.config.EnvConfig` (each declared once there, with its unit, range and
    reason; the table is generated into ``docs/environment.md``), ``params`` (a GripperParams or
    a parameter file), ``calibration`` (a ``gripper calibrate`` file) and the renderer's
    ``render_mode``, ``width``, ``height``, ``camera``.

    ## Version history

    - v0: first version (mujoco 4, 2 ms physics step, hobby servo).
    - v0, package 0.4.0: sparse constraint Jacobian and no constraint islands (the same problem,
      other rounding), the bag's pack touches its film stiffly. Spaces, rewards and episode rules
      are unchanged, but episodes are not bitwise those of 0.3.0 for the same seed.
    - v0, package 0.5.0: a closed cut is the squeezed silicone teeth (1.72 N·m/rad at small
      overrun, stiffening, ``springs.closure``), no longer a hard stop whose give grew with the
      step: fingers closed at the servo's stall wrap a little further. Spaces, rewards and episode rules are
      unchanged; episodes differ from 0.4.x for the same seed.
    - v0, package 0.5.1: under the 2 ms discrete integrator the closed cuts are matched to
      their design (they were up to 1.8x stiffer at the fingertip); episodes differ from 0.5.0.
    - v1, package 0.6.0: the hinge springs are the committed calibration of the default design
      (fitted to the mesh-converged continuum reference, ``docs/calibration.md``) instead of
      paper 000's Table 2 number, and the default bridge is the one that makes Table 2's spring
      (read per radian) consistent with the silicone (``docs/consistency.md``). Spaces, rewards
      and episode rules are unchanged; the dynamics are not, hence the new version. v0 is
      no longer registered.
    - v1, package 0.7.0: unchanged (the package was layered); seeded episodes are bitwise
      those of 0.6.0 (``scripts/fingerprint.py``).
    - v1, package 0.8.0: unchanged (object files, hardened inputs); seeded episodes are bitwise
      those of 0.7.0. Objects may be object files; ``info["object"]`` is the object's name.
    - v2, package 0.9.0: the observation gains the servos' sensed position, current and spool
      tension (96 entries, was 84). The dynamics, rewards and episode rules are unchanged.
      v1 is no longer registered.
    - v3, package 0.10.0: the paper box's and the bag's meshes are 4 x 4 x 5 points (were
      5 x 5 x 6; their convergence check is in ``docs/performance.md``), so episodes with those
      objects have other dynamics; the rigid objects and the balloon are unchanged, and so are
      the spaces, rewards and episode rules. v2 is no longer registered.
    - v4, package 0.11.0: a standard RL algorithm learns the task (``docs/environment.md``:
      why v3 taught nothing, and the baselines). The palm
      and the servo actions are velocities (``palm_control``, ``servo_control``; ``"position"``
      keeps v3's set-points); the observation gains the servo and palm set-points and each
      finger's contact force on the object (107 entries, was 96); the rigid objects' damage
      reads that force (v3 read the pads' touch sensors, which the curled grasp never touches,
      so it was always 0), and so does the contact reward, now off by default; the reach reward
      is 1 - tanh(d / 5 cm) (was -d); success no longer ends the episode. The physics is
      unchanged. v3 is no longer registered.
    - v5, package 0.12.0: the library's ``"bag"`` is a zipper storage bag holding two loose
      bricks (``gripper/data/objects/bag.toml``); the pack-in-a-bag of v4 is ``"bag_pack"``.
      Episodes with the bag have other dynamics; the rigid objects, the balloon and the paper
      box, the spaces, rewards and episode rules are unchanged. v4 is no longer registered.
    - v6, package 0.15.0: the cable fingers' hinge springs are the recalibrated default (the
      reference's static points relaxed to rest, ``docs/calibration.md``), so every episode has
      other dynamics; the spaces, rewards and episode rules are unchanged. ``actuation="pneumatic"``
      is new (the pneumatic gripper, its own spaces: ``docs/pneumatic_gripper.md``). v5 is no
      longer registered.
    - v7, package 0.16.0: observations and rewards on the scales a default PPO or SAC expects,
      inside the environment: each observation part is divided by its characteristic magnitude
      (``scale_observations``, ``gripper.envs.config.OBSERVATION_SCALES``; ``env.observation_divisor``
      turns it back into SI units), and the dense reward's weights are v6's divided by 8 (the
      best step pays 1). The physics and the episode rules are unchanged. v6 is no longer
      registered.
    - v8, package 0.17.0: contact from the silicone (issue 44): every finger element sits on a
      compliant pad whose springs follow Hertz's law for its material, the elements' edges are
      rounded, and rigid parts' contacts are near-rigid (``gripper.parts.pads``,
      ``docs/contact.md``), so the squeeze and holding forces, and with them every episode's
      dynamics, change. The spaces, rewards and episode rules are unchanged. v7 is no longer
      registered.
    - v9, package 0.18.0: the drives became components (``gripper.drives``); the cable
      gripper's episodes are bit for bit v8's. The pneumatic gripper's segment meshes now lie on
      the pads' micrometre grid, as its committed model file (``models/pneumatic_gripper``) holds
      them, so its episodes move by up to 0.04 % in a force. The spaces, rewards and episode
      rules are unchanged. v8 is no longer registered.
    - v10, package 0.20.0: the pneumatic finger recalibrated from the corrected finite-element
      model of paper 001's actuator (``docs/pneumatic.md``): its springs, stiffening, knee and
      chamber moment change, so the pneumatic gripper's episodes change. The cable gripper's
      are v9's. The spaces, rewards and episode rules are unchanged. v9 is no longer registered.
    - v11, package 0.21.0: the default cable gripper chosen by the gripping-range study
      (``docs/envelope.md``): its palm radius, its fingers' splay and its tapered tips change,
      and the palm sits on a wrist, which the environment holds at zero yaw. Every episode's
      dynamics change. The spaces, rewards and episode rules are unchanged. v10 is no longer
      registered.

    - v12, package 0.22.0: the dense reward is a ladder (issue 49): reach pays only with open
      fingers, contact pays again (0.2, only with opposing fingers pressing, weighted by the
      distance to the grasp point), lift 0.2 and success 0.6 (were reach 0.125, contact 0, lift
      0.25, success 0.625). The physics, spaces, sparse reward and episode rules are unchanged.
      The goal-conditioned variant ``SoftGripperGraspGoal-v12`` is new
      (:mod:`gripper.envs.goal_env`). v11 is no longer registered.

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

    def servo_action(self, angle: float) -> float:
        """Action value that sets a servo's spool angle to ``angle`` [rad]."""
        return self._scene_for_actions().servo_action(angle)

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

