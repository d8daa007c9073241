"""What the single and the vector Gymnasium environments share: scenes, actions, observation,
reward, success and episode end, all computed from one simulation's state and sensor data.

Both environments step with ``mujoco.rollout`` (one control period = ``frame_skip`` physics
steps) from a full-physics state with a zero solver warm start, and build every quantity from
the rollout's final state and last sensor row, so a single environment and one slot of the vector
environment produce bitwise the same episode for the same seed.

Example:
    >>> from gripper.envs.config import EnvConfig
    >>> from gripper.envs.task import observation_structure
    >>> observation_structure(EnvConfig().validate())["hinge_angle"]
    (0, 20, 'rad')
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.drives import drive_for
from gripper.envs.config import (
    CONTACT_FORCE,
    HELD,
    IDENTITY_QUAT,
    OBSERVATION_SCALES,
    OPPOSING_ANGLE,
    REACH_SCALE,
    START_CLEARANCE,
    TIP_FLOOR_CLEARANCE,
    WORKSPACE_FLOOR,
    WORKSPACE_RADIUS,
    XY_ACTION_RANGE,
    EnvConfig,
)
from gripper.experiments.approach import check_fits_opening
from gripper.experiments.protocol import TrialNoise, is_held
from gripper.experiments.trial import sample_placement
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.damage import running_damage_measure
from gripper.sim.probes import ObjectProbe
from gripper.sim.scene import build_grasp_scene, trial_params
from gripper.sim.stepping import STATE_SPEC

CTRL_SPEC = int(mujoco.mjtState.mjSTATE_CTRL)


@dataclass(frozen=True)
class ObservationTerm:
    """One named part of the observation: its unit, its size (a function of the config) and
    the function that computes it from a step's :class:`ObservationInputs`."""

    name: str
    unit: str
    size: Callable[[EnvConfig], int]
    value: Callable[[ObservationInputs], np.ndarray]


def _per_finger(cfg: EnvConfig) -> int:
    return cfg.n_fingers


def _per_hinge(cfg: EnvConfig) -> int:
    return cfg.n_fingers * len(drive_for(cfg.params).names(0).hinges)


def _per_segment(cfg: EnvConfig) -> int:
    return cfg.n_fingers * drive_for(cfg.params).names(0).n_segments


def _drive_state(i: int) -> Callable[[ObservationInputs], np.ndarray]:
    return lambda o: o.drive_state[i]


def _drive_sensed(i: int) -> Callable[[ObservationInputs], np.ndarray]:
    return lambda o: o.drive_sensed[i]


def observation_terms(cfg: EnvConfig) -> tuple[ObservationTerm, ...]:
    """The observation, term by term, in order: the one table that its layout
    (:func:`observation_structure`), its scales (:func:`observation_divisor`) and every step's
    observation (:func:`observe`) are read from. The drive's own parts (its
    ``state_observations``, one entry per finger each) follow the hinge velocities, and what its
    hardware reports (``sensed_observations``) comes last: the cable gripper's cable, servo and
    spool readings; the pneumatic gripper's regulators' pressures, as fractions of the highest
    set-point (``pneumatic.pressure_max``)."""
    drive = drive_for(cfg.params)
    return (
        ObservationTerm("hinge_angle", "rad", _per_hinge, lambda o: o.data.qpos[o.scene.hinge_q]),
        ObservationTerm("hinge_velocity", "rad/s", _per_hinge, lambda o: o.data.qvel[o.scene.hinge_v]),
        *[ObservationTerm(name, unit, _per_finger, _drive_state(i))
          for i, (name, unit) in enumerate(drive.state_observations)],
        ObservationTerm("palm_height", "m", lambda c: 1, lambda o: o.palm[2:3]),
        ObservationTerm("palm_setpoint", "m", lambda c: 3, _palm_setpoint),
        ObservationTerm("object_pos_rel_palm", "m", lambda c: 3,
                        lambda o: o.scene.probe.object_pos(o.data) - o.palm),
        ObservationTerm("object_quat", "-", lambda c: 4, _object_quat),
        ObservationTerm("pad_force", "N", _per_segment, lambda o: o.sens[o.scene.pads]),
        ObservationTerm("finger_object_force", "N", _per_finger, lambda o: o.scene.probe.finger_forces(o.data)),
        *[ObservationTerm(name, unit, _per_finger, _drive_sensed(i))
          for i, (name, unit) in enumerate(drive.sensed_observations)],
    )


def observation_structure(cfg: EnvConfig) -> dict[str, tuple[int, int, str]]:
    """Observation layout: name -> (start index, size, unit), from :func:`observation_terms`."""
    out, i = {}, 0
    for term in observation_terms(cfg):
        size = term.size(cfg)
        out[term.name] = (i, size, term.unit)
        i += size
    return out


def observation_divisor(cfg: EnvConfig) -> np.ndarray:
    """What each observation entry is divided by before it is returned: its part's scale
    (:data:`gripper.envs.config.OBSERVATION_SCALES`) with ``scale_observations``, else 1."""
    out = []
    for name, (_, size, _) in observation_structure(cfg).items():
        out += [OBSERVATION_SCALES[name][0] if cfg.scale_observations else 1.0] * size
    return np.array(out)


class Scene:
    """One compiled scene (gripper + one object) and the indices the environment reads."""

    def __init__(self, cfg: EnvConfig, obj: GraspObject, place: Placement):
        p = trial_params(cfg.params)
        self.cfg, self.obj, self.params = cfg, obj, p
        self.model = build_grasp_scene(p, obj, place)
        m = self.model
        self.drive = drive = drive_for(p)
        self.probe = ObjectProbe(m, obj, cfg.n_fingers, drive)
        nf = cfg.n_fingers
        names = [drive.names(k) for k in range(nf)]
        hinges = [h for n in names for h in n.hinges]
        self.hinge_q = np.array([m.jnt_qposadr[m.joint(h).id] for h in hinges])
        self.hinge_v = np.array([m.jnt_dofadr[m.joint(h).id] for h in hinges])
        self.lift_q = {a: m.jnt_qposadr[m.joint(a).id] for a in ("lift_x", "lift_y", "lift_z")
                       if mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, a) >= 0}
        sadr = lambda name: m.sensor_adr[m.sensor(name).id]  # noqa: E731
        self.pads = np.array([sadr(pad) for n in names for pad in n.pads])
        self.drive_act = self.probe.actuators  # each finger's drive actuator (a servo, a chamber's regulator, ...)
        self.sensor = drive.sensor(m)
        self.act_lift = {a: m.actuator(a).id for a in self.lift_q}
        self.lift_act_ids = np.array(list(self.act_lift.values()))
        self.home = p.lift.home_height
        self.z_min = drive.finger_length + TIP_FLOOR_CLEARANCE - self.home
        self.z_start = obj.height + drive.finger_length + START_CLEARANCE - self.home
        self.z_max = 0.0  # the lift's home: palm face at params.lift.home_height
        # the top of the drive's command range (a servo's travel [rad], a regulator's highest set-point [Pa])
        self.command_max = float(m.actuator_ctrlrange[self.drive_act[0], 1])
        # finger pairs that oppose each other across the palm (azimuths 2πk/n apart by >= OPPOSING_ANGLE)
        gap = lambda i, j: abs(math.remainder(2.0 * math.pi * (i - j) / nf, 2.0 * math.pi))  # noqa: E731
        self.opposing = np.array([(i, j) for i in range(nf) for j in range(i + 1, nf) if gap(i, j) >= OPPOSING_ANGLE],
                                 dtype=int).reshape(-1, 2)
        self.free_q = (m.jnt_qposadr[m.joint("object_free").id]
                       if mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, "object_free") >= 0 else -1)
        self.nominal_mass = m.body_mass.copy()
        self.nominal_inertia = m.body_inertia.copy()
        self.nominal_friction = m.geom_friction.copy()
        self.nstate = mujoco.mj_stateSize(m, STATE_SPEC)
        self.observation_terms = observation_terms(cfg)
        self._signature: tuple | None = None
        self._build_control_map()
        # observation gather: palm x/y joints (or none), object body (or the flex centroid)
        self.palm_xy_q = np.array([self.lift_q[a] for a in ("lift_x", "lift_y") if a in self.lift_q], dtype=int)
        self.palm_xy_slot = np.array([i for i, a in enumerate(("lift_x", "lift_y")) if a in self.lift_q], dtype=int)
        self.palm_xy_act = np.array([self.act_lift[a] for a in ("lift_x", "lift_y") if a in self.lift_q], dtype=int)

    def signature(self) -> tuple:
        """Sizes that decide whether scenes can share one rollout call (cached: read every step)."""
        if self._signature is None:
            m = self.model
            self._signature = (m.nq, m.nv, m.na, m.nu, m.nsensordata, self.nstate)
        return self._signature

    def lift_action(self, palm_height: float) -> float:
        """The lift action that sets the palm face ``palm_height`` above the floor [m]."""
        z = palm_height - self.home
        return float(np.clip(2.0 * (z - self.z_min) / (self.z_max - self.z_min) - 1.0, -1.0, 1.0))

    def xy_action(self, offset: float) -> float:
        """The x or y action that sets the palm ``offset`` from its home axis [m]."""
        return float(np.clip(offset / XY_ACTION_RANGE, -1.0, 1.0))

    def command_action(self, command: float) -> float:
        """The finger action that sets the drive's command to ``command`` (its unit: a servo's
        spool angle [rad], a regulator's pressure set-point [Pa])."""
        return float(np.clip(2.0 * command / self.command_max - 1.0, -1.0, 1.0))

    def controls(self, action: np.ndarray, previous: np.ndarray) -> np.ndarray:
        """Map an action in [-1, 1] to the actuator controls (nu,), given the ``previous``
        control period's controls.

        The drive's actuators (their command in [0, command_max]) by ``servo_control``, palm
        stages (lift z in [z_min, z_max], x/y in ±XY_ACTION_RANGE) by ``palm_control``:
        ``"position"``, the set-point mapped linearly from [-1, 1] onto its range;
        ``"velocity"``, the previous set-point moved by ``action × speed × control period`` and
        kept in its range (drive: its ``command_rate``; palm: ``palm_speed``). Actuators without
        an action stay at 0."""
        a = np.clip(action, -1.0, 1.0)[self._ctrl_source]
        u = self._ctrl_offset + self._ctrl_scale * a
        for idx, step, lo, hi in self._velocity:
            u[idx] = np.clip(previous[idx] + step * a[idx], lo, hi)
        return u

    def _build_control_map(self) -> None:
        nu = self.model.nu
        self._ctrl_source = np.zeros(nu, dtype=int)
        self._ctrl_offset = np.zeros(nu)
        self._ctrl_scale = np.zeros(nu)
        fingers = self.cfg.action_mode == "fingers"
        k = self.cfg.n_fingers if fingers else 1
        self._ctrl_source[self.drive_act] = np.arange(k) if fingers else 0  # synergy: one command
        self._ctrl_offset[self.drive_act] = self._ctrl_scale[self.drive_act] = 0.5 * self.command_max
        z = self.act_lift["lift_z"]
        self._ctrl_source[z] = k
        self._ctrl_offset[z] = 0.5 * (self.z_min + self.z_max)
        self._ctrl_scale[z] = 0.5 * (self.z_max - self.z_min)
        palm, lo, hi = [z], [self.z_min], [self.z_max]
        if self.cfg.xy_actions:
            for j, name in enumerate(("lift_x", "lift_y")):
                self._ctrl_source[self.act_lift[name]] = k + 1 + j
                self._ctrl_scale[self.act_lift[name]] = XY_ACTION_RANGE
                palm.append(self.act_lift[name])
                lo.append(-XY_ACTION_RANGE)
                hi.append(XY_ACTION_RANGE)
        dt = self.cfg.control_period
        # velocity-controlled actuators: (indices, step per unit action, lower, upper bounds)
        self._velocity: list[tuple[np.ndarray, float, np.ndarray | float, np.ndarray | float]] = []
        if self.cfg.palm_control == "velocity":
            self._velocity.append((np.array(palm), self.cfg.palm_speed * dt, np.array(lo), np.array(hi)))
        if self.cfg.servo_control == "velocity":
            # the drive's rate: the servo's slew rate, the regulator's set-point at the grasp protocol's ramp
            rate = self.drive.command_rate(HELD)
            self._velocity.append((np.asarray(self.drive_act), rate * dt, 0.0, self.command_max))


class SceneSet:
    """The scenes of an environment: rigid objects compiled once and placed through their free
    joint; deformable ones (flexes) compiled anew at every reset with the sampled placement."""

    def __init__(self, cfg: EnvConfig):
        self.cfg = cfg
        self.objects = [check_fits_opening(get_object(n), cfg.params) for n in cfg.objects]
        self._rigid = {o.name: Scene(cfg, o, Placement()) for o in self.objects if not o.is_flex}

    @staticmethod
    def apply_placement(scene: Scene, place: Placement) -> None:
        """Set a rigid scene's object mass, inertia and friction from the nominal values."""
        m, b = scene.model, scene.probe.body
        m.body_mass[:] = scene.nominal_mass
        m.body_inertia[:] = scene.nominal_inertia
        m.geom_friction[:] = scene.nominal_friction
        m.body_mass[b] *= place.mass_scale
        m.body_inertia[b] *= place.mass_scale
        m.geom_friction[scene.probe.object_geom[:-1], 0] *= place.friction_scale

    def new_episode(self, rng: np.random.Generator) -> tuple[Scene, mujoco.MjData, Placement, int]:
        """A new episode's scene, data, placement and seed (the placement's and the sensor
        noise's)."""
        obj = self.objects[int(rng.integers(len(self.objects)))]
        noise = TrialNoise(xy=self.cfg.pose_noise, yaw=self.cfg.yaw_noise, mass_frac=self.cfg.mass_noise,
                           friction_frac=self.cfg.friction_noise)
        seed = int(rng.integers(2**63 - 1))
        place = sample_placement(obj, noise, seed, 0)
        if obj.is_flex:
            scene = Scene(self.cfg, obj, place)
        else:
            scene = self._rigid[obj.name]
            self.apply_placement(scene, place)
        d = mujoco.MjData(scene.model)
        if not obj.is_flex:
            a = scene.free_q
            d.qpos[a:a + 2] = [place.x, place.y]
            d.qpos[a + 3:a + 7] = [math.cos(0.5 * place.yaw), 0.0, 0.0, math.sin(0.5 * place.yaw)]
        d.qpos[scene.lift_q["lift_z"]] = scene.z_start
        d.ctrl[scene.act_lift["lift_z"]] = scene.z_start
        mujoco.mj_forward(scene.model, d)
        return scene, d, place, seed


@dataclass
class EpisodeState:
    """Per-episode bookkeeping of one simulation."""

    scene: Scene
    data: mujoco.MjData
    placement: Placement
    start_pos: np.ndarray
    hold_ref: np.ndarray | None = None
    hold_steps: int = 0
    peak_strain: float = 0.0
    damaged: bool = False
    last_obs: np.ndarray | None = None
    steps: int = 0
    sensor_rng: np.random.Generator | None = None


def start_episode(scenes: SceneSet, rng: np.random.Generator) -> EpisodeState:
    scene, d, place, seed = scenes.new_episode(rng)
    return EpisodeState(scene=scene, data=d, placement=place, start_pos=scene.probe.object_pos(d),
                        sensor_rng=np.random.default_rng([seed, 1]))


def state_vector(ep: EpisodeState) -> np.ndarray:
    out = np.empty(ep.scene.nstate)
    mujoco.mj_getState(ep.scene.model, ep.data, out, STATE_SPEC)
    return out


def load_state(ep: EpisodeState, state: np.ndarray, ctrl: np.ndarray) -> None:
    """Put the rollout's final state into the episode's data and compute its contacts and
    contact forces (``mj_forward``, which changes no state: the finger-object forces of the
    observation, the reward and the rigid objects' damage are read from it)."""
    m, d = ep.scene.model, ep.data
    mujoco.mj_setState(m, d, state, STATE_SPEC)
    d.ctrl[:] = ctrl
    mujoco.mj_forward(m, d)


class ObservationInputs:
    """What the observation terms of one step read: the episode's scene and data, the last
    sensor row, and the quantities several terms share, each computed once on first use (the
    drive's sensor reading draws its noise from the episode's generator)."""

    def __init__(self, ep: EpisodeState, sens: np.ndarray):
        self.ep, self.scene, self.data, self.sens = ep, ep.scene, ep.data, sens

    @functools.cached_property
    def palm(self) -> np.ndarray:
        """The palm centre [m, world frame]: x/y from their stages (0 without), z its face's height."""
        s, q = self.scene, self.data.qpos
        palm = np.zeros(3)
        palm[s.palm_xy_slot] = q[s.palm_xy_q]
        palm[2] = s.home + q[s.lift_q["lift_z"]]
        return palm

    @functools.cached_property
    def drive_state(self) -> list[np.ndarray]:
        return self.scene.drive.observe_state(self.scene.model, self.data, self.sens)

    @functools.cached_property
    def drive_sensed(self) -> list[np.ndarray]:
        s = self.scene
        return s.drive.observe_sensed(s.model, s.sensor.read(self.sens, self.ep.sensor_rng))


def _palm_setpoint(o: ObservationInputs) -> np.ndarray:
    s, ctrl = o.scene, o.data.ctrl
    setpoint = np.zeros(3)
    setpoint[s.palm_xy_slot] = ctrl[s.palm_xy_act]
    setpoint[2] = s.home + ctrl[s.act_lift["lift_z"]]
    return setpoint


def _object_quat(o: ObservationInputs) -> np.ndarray:
    body = o.scene.probe.body
    return o.data.xquat[body] if body >= 0 else IDENTITY_QUAT


def observe(ep: EpisodeState, sens: np.ndarray) -> np.ndarray:
    """The observation (float64) from the data's current state and the last sensor row: the
    scene's :func:`observation_terms`, in order."""
    inputs = ObservationInputs(ep, sens)
    return np.concatenate([term.value(inputs) for term in ep.scene.observation_terms])


def evaluate(ep: EpisodeState, obs: np.ndarray, sens: np.ndarray, action: np.ndarray, cfg: EnvConfig,
             struct: dict) -> tuple[float, bool, dict]:
    """Reward, termination and info of the control step that ended in ``ep``'s current state."""
    s, d = ep.scene, ep.data
    obj_pos = s.probe.object_pos(d)
    height = float(obj_pos[2] - ep.start_pos[2])
    rel = obs[struct["object_pos_rel_palm"][0]:struct["object_pos_rel_palm"][0] + 3]
    # scalar math on 3-vectors: numpy's per-call cost dominates at this size
    reach = math.dist(rel, (0.0, 0.0, -0.5 * s.drive.finger_length))  # to the grasp point
    i = struct["finger_object_force"][0]
    finger = obs[i:i + cfg.n_fingers]  # each finger's normal force on the object, all element faces
    pressing = finger > CONTACT_FORCE
    # contact: the fraction of fingers pressing, counted only when two opposing fingers press
    opposed = bool((pressing[s.opposing[:, 0]] & pressing[s.opposing[:, 1]]).any()) if len(s.opposing) else False
    touching = float(np.count_nonzero(pressing)) / cfg.n_fingers if opposed else 0.0
    near = 1.0 - math.tanh(reach / REACH_SCALE)
    openness = 1.0 - float(np.mean(d.ctrl[s.drive_act])) / s.command_max
    # damage: the object's own criterion where it can be read at every step
    if s.obj.reads_strain:
        ep.peak_strain = max(ep.peak_strain, s.probe.edge_strain(d))
    measure = running_damage_measure(s.model, d, s.obj, s.probe, peak_strain=ep.peak_strain,
                                     total_force=float(finger.sum()))
    newly_damaged = (not ep.damaged) and s.obj.is_damaged(measure)
    ep.damaged = ep.damaged or newly_damaged
    # held (the benchmark's rule): lifted past the success height and not slipping relative to
    # the palm since the hold began; a slip restarts the hold from here
    if height >= HELD.success_height and not ep.damaged:
        slip = math.dist(rel, ep.hold_ref) if ep.hold_ref is not None else 0.0
        if ep.hold_ref is None or not is_held(height, slip, HELD):
            ep.hold_ref, ep.hold_steps = rel.copy(), 0
        ep.hold_steps += 1
    else:
        ep.hold_ref, ep.hold_steps = None, 0
    held_s = ep.hold_steps * cfg.control_period
    is_success = held_s >= cfg.success_hold_s - 1e-9
    w = cfg.weights
    terms = {
        "reward_reach": w["reach"] * near * openness,
        "reward_contact": w["contact"] * near * touching,
        "reward_lift": w["lift"] * min(1.0, max(0.0, height / HELD.success_height)),
        "reward_success": w["success"] * float(is_success),
        "reward_damage": -w["damage"] * float(newly_damaged),
        "reward_action": -w["action"] * float(action @ action),
    }
    reward = float(sum(terms.values())) if cfg.reward_type == "dense" else float(is_success)
    out_of_workspace = bool(math.hypot(obj_pos[0], obj_pos[1]) > WORKSPACE_RADIUS or obj_pos[2] < WORKSPACE_FLOOR)
    terminated = out_of_workspace or ep.damaged or (cfg.terminate_on_success and is_success)
    info = {**terms, "is_success": bool(is_success), "object": s.obj.name, "object_height_m": height,
            "held_s": held_s, "damaged": ep.damaged, "damage_measure": measure,
            "out_of_workspace": out_of_workspace, "unstable": False}
    return reward, terminated, info


def unstable_result(ep: EpisodeState, err: str) -> tuple[np.ndarray, float, bool, dict]:
    """A diverged simulation ends the episode: last finite observation, zero reward, the reason."""
    assert ep.last_obs is not None, "an episode observes on reset"
    return (ep.last_obs.copy(), 0.0, True,
            {"is_success": False, "object": ep.scene.obj.name, "unstable": True, "error": err})


class BatchStepper:
    """Steps several episodes one control period each with one ``mujoco.rollout`` call per group
    of scenes with the same sizes, on MuJoCo's thread pool (``nthread`` threads; 0: this thread).

    Instability: a non-finite final state, a clock that did not advance by the control period
    (MuJoCo resets a diverging simulation after its warning), or a MuJoCo warning. Warnings are
    counted in the rollout's per-thread scratch data, which do not say which episode raised them,
    so when one appears without a reset clock, the batch's episodes are replayed one by one
    (deterministic: same state, same zero warm start) to find the culprits.
    """

    def __init__(self, nthread: int = 0):
        from mujoco import rollout

        self.nthread = nthread
        self.roll = rollout.Rollout(nthread=nthread)
        self._scratch: dict[tuple, list[mujoco.MjData]] = {}
        self._counters: dict[tuple, list[np.ndarray]] = {}

    def _warning_counters(self, datas: list[mujoco.MjData]) -> list[np.ndarray]:
        """Views of each scratch data's warning counters (made once: the view costs more than
        reading it)."""
        key = tuple(id(d) for d in datas)
        if key not in self._counters:
            self._counters[key] = [d.warning.number for d in datas]
        return self._counters[key]

    def _datas(self, scene: Scene) -> list[mujoco.MjData]:
        key = scene.signature()
        if key not in self._scratch:
            self._scratch[key] = [mujoco.MjData(scene.model) for _ in range(max(1, self.nthread))]
        return self._scratch[key]

    def _run(self, eps, ctrls, datas):
        n, k = len(eps), eps[0].scene.cfg.frame_skip
        s0 = np.stack([state_vector(ep) for ep in eps])
        new = np.stack(ctrls)
        u = np.repeat(new[:, None, :], k, axis=1)
        # palm stages: first-order hold, the set-point ramps from the last one to the new one over
        # the control period (a stage's trajectory generator); a jump would jerk the stiff stage.
        # Scenes of one size signature come from one config, so their lift actuators coincide.
        lift = eps[0].scene.lift_act_ids
        if any(ep.scene.lift_act_ids is not lift and not np.array_equal(ep.scene.lift_act_ids, lift)
               for ep in eps):
            raise ValueError("batch: episodes with different lift actuators cannot share a rollout")
        ramp = (np.arange(1, k + 1) / k)[None, :, None]
        prev = np.stack([ep.data.ctrl for ep in eps])[:, lift]
        u[:, :, lift] = prev[:, None, :] + ramp * (new[:, lift] - prev)[:, None, :]
        warm = np.zeros((n, eps[0].scene.model.nv))
        state = np.empty((n, k, s0.shape[1]))
        sens = np.empty((n, k, eps[0].scene.model.nsensordata))
        counters = self._warning_counters(datas)
        for c in counters:
            c[:] = 0  # read after the rollout
        self.roll.rollout([ep.scene.model for ep in eps], datas, s0, u, control_spec=CTRL_SPEC,
                          skip_checks=True, nstep=k, initial_warmstart=warm, state=state,
                          sensordata=sens, chunk_size=1)
        warned = any(c.any() for c in counters)
        # MuJoCo resets a diverging simulation (time back to 0) after its warning: the clock
        # tells, per episode, even where the per-thread warning counters cannot
        dt = eps[0].scene.model.opt.timestep
        reset = np.abs(state[:, -1, 0] - (s0[:, 0] + k * dt)) > 0.5 * dt
        return state[:, -1], sens[:, -1], warned, reset

    def step(self, eps: list[EpisodeState], ctrls: list[np.ndarray]) -> list[tuple[np.ndarray, str | None]]:
        """Advance each episode one control period; return (last sensor row, error or None)."""
        out: list = [None] * len(eps)
        groups: dict[tuple, list[int]] = {}
        for i, ep in enumerate(eps):
            groups.setdefault(ep.scene.signature(), []).append(i)
        for idx in groups.values():
            batch = [eps[i] for i in idx]
            datas = self._datas(batch[0].scene)
            final, sens, warned, reset = self._run(batch, [ctrls[i] for i in idx], datas)
            culprits = set(np.flatnonzero(reset).tolist())
            if warned and not culprits:
                for j, i in enumerate(idx):
                    if self._run([eps[i]], [ctrls[i]], datas)[2]:  # the pool needs one data per thread
                        culprits.add(j)
            finite = np.isfinite(final).all(axis=1)
            for j, i in enumerate(idx):
                err = None
                if j in culprits:
                    err = "MuJoCo warning during the step (simulation unstable)"
                elif not finite[j]:
                    err = "non-finite state (simulation diverged)"
                else:
                    load_state(eps[i], final[j], ctrls[i])
                out[i] = (sens[j], err)
        return out

    def close(self) -> None:
        self.roll.close()
