"""One scripted grasp trial, and the pull-out test, on the gripper with one object.

The trial is open loop (every command is a function of time), so each phase is stepped with
``mujoco.rollout`` in chunks of ``protocol.chunk_steps`` steps on the trial's own ``MjData``;
between chunks the runner checks stability (MuJoCo warnings, non-finite state), slip and
damage. Cable tension is the tendon-limit force sensor, recorded at every step by the rollout;
per-finger contact force is the sum of the normal forces of all contacts between that finger's
elements and the object, read from the contact list at the end of every chunk (so peaks are
sampled every ``chunk_steps`` steps, 20 ms by default at the 2 ms step).

Example:
    >>> from gripper.trial import run_trial
    >>> rec = run_trial("block", seed=0, index=0)          # doctest: +SKIP
    >>> rec["success"], rec["peak_total_force_N"]          # doctest: +SKIP
"""

from __future__ import annotations

import hashlib
import json
import math
import time
import zlib
from dataclasses import dataclass

import mujoco
import numpy as np
from mujoco import rollout

import gripper
from gripper.canonical import apply_canonical_constants
from gripper.closure import tune_closure_limits
from gripper.model import build_scene_spec, finger_name
from gripper.objects import CONTENTS_BODY, OBJECT_BODY, GraspObject, Placement, add_object, get_object
from gripper.params import GripperParams
from gripper.protocol import GraspProtocol, TrialNoise
from gripper.stability import SimulationUnstable, check_stable

STATE_SPEC = mujoco.mjtState.mjSTATE_FULLPHYSICS
CTRL_SPEC = int(mujoco.mjtState.mjSTATE_CTRL)
# Objects whose damage measure is the peak edge strain of their flex (burst, tear).
STRAIN_DAMAGE_KINDS = ("balloon", "bag")

# Elastic spring-back before measuring a permanent dent: contacts and gravity off, this long [s];
# the paper box's slowest wall mode (≈ 30 Hz) and its Rayleigh damping settle well within it.
SPRINGBACK_S = 0.3


def versions() -> dict[str, str]:
    return {"mujoco": mujoco.__version__, "gripper": gripper.__version__, "numpy": np.__version__}


def config_hash(*parts) -> str:
    """SHA-256 (first 16 hex digits) of the JSON of ``parts`` (sorted keys)."""
    blob = json.dumps(parts, sort_keys=True, default=str).encode()
    return hashlib.sha256(blob).hexdigest()[:16]


def sample_placement(obj: GraspObject, noise: TrialNoise, seed: int, index: int) -> Placement:
    """The perturbation of trial ``index`` of a run with base ``seed``: deterministic, and the
    same whichever process runs it (the generator is seeded by seed, index and object name)."""
    rng = np.random.default_rng([seed, index, zlib.crc32(obj.name.encode())])
    x, y = rng.uniform(-noise.xy, noise.xy, size=2)
    yaw = rng.uniform(-math.pi, math.pi)
    ms = rng.uniform(1 - noise.mass_frac, 1 + noise.mass_frac)
    fs = rng.uniform(1 - noise.friction_frac, 1 + noise.friction_frac)
    return Placement(x=float(x), y=float(y), yaw=float(yaw) if noise.yaw and not obj.yaw_symmetric else 0.0,
                     mass_scale=float(ms), friction_scale=float(fs))


def grasp_scene_spec(p: GripperParams, *, with_object: bool = False) -> mujoco.MjSpec:
    """The gripper scene as grasp trials step it: ``discrete`` integrator (see objects), with the
    closed cuts matched to their design under that integrator (:mod:`gripper.closure`)."""
    spec = build_scene_spec(p, with_object=with_object)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    tune_closure_limits(spec, p, spec.compile())
    return spec


def build_grasp_scene(p: GripperParams, obj: GraspObject, place: Placement) -> mujoco.MjModel:
    """Compile the gripper scene with ``obj`` at ``place`` (:func:`grasp_scene_spec`)."""
    spec = grasp_scene_spec(p)
    add_object(spec, obj, place)
    m = spec.compile()
    apply_canonical_constants(m, obj, place)  # same numbers in every process (gripper.canonical)
    return m


@dataclass
class _Probe:
    """Indices into the model for the quantities the trial reads."""

    model: mujoco.MjModel
    obj: GraspObject
    n_fingers: int

    def __post_init__(self):
        m = self.model
        self.servo = np.array([m.actuator(f"{finger_name(k)}_servo").id for k in range(self.n_fingers)])
        self.lift_x = m.actuator("lift_x").id
        self.lift_z = m.actuator("lift_z").id
        self.palm = m.body("palm").id
        # finger index of every geom (-1: not a finger element), object geoms
        self.geom_finger = np.full(m.ngeom + 1, -1)  # last entry: index -1 (flex side)
        for g in range(m.ngeom):
            name = m.body(m.geom_bodyid[g]).name
            for k in range(self.n_fingers):
                if name.startswith(f"{finger_name(k)}_seg"):
                    self.geom_finger[g] = k
        self.object_geom = np.zeros(m.ngeom + 1, dtype=bool)
        for g in range(m.ngeom):
            if m.body(m.geom_bodyid[g]).name in (OBJECT_BODY, CONTENTS_BODY):
                self.object_geom[g] = True
        self.tension_adr = np.array([m.sensor_adr[m.sensor(f"{finger_name(k)}_cable_tension").id]
                                     for k in range(self.n_fingers)])
        self.flex = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_FLEX, OBJECT_BODY) if self.obj.is_flex else -1
        if self.flex >= 0:
            a, n = m.flex_vertadr[self.flex], m.flex_vertnum[self.flex]
            self.vert = slice(a, a + n)
            a, n = m.flex_edgeadr[self.flex], m.flex_edgenum[self.flex]
            self.edge_verts = m.flex_edge[a:a + n]  # local vertex pairs
            d0 = mujoco.MjData(m)
            mujoco.mj_kinematics(m, d0)
            mujoco.mj_flex(m, d0)
            self.rest_verts = d0.flexvert_xpos[self.vert].copy()
            self.edge_length0 = self._edge_lengths(self.rest_verts)
        self.q_adr = None  # no per-step strain map (set for objects whose damage is a strain)
        if self.flex >= 0 and self.obj.kind in STRAIN_DAMAGE_KINDS:
            self._vertex_map(m, d0)
        if self.obj.kind == "bag":
            self.body = m.body(CONTENTS_BODY).id
        elif not self.obj.is_flex:
            self.body = m.body(OBJECT_BODY).id
        else:
            self.body = -1
        bodies = [self.body] if self.body >= 0 else []
        if self.flex >= 0:
            bodies += sorted({int(b) for b in m.flex_nodebodyid[
                m.flex_nodeadr[self.flex]:m.flex_nodeadr[self.flex] + m.flex_nodenum[self.flex]]}
                if m.flex_interp[self.flex] else
                {int(b) for b in m.flex_vertbodyid[self.vert]})
        self.object_bodies = np.array([b for b in bodies if b > 0])

    def object_pos(self, d: mujoco.MjData) -> np.ndarray:
        """Reference point of the object [m]: body origin (rigid, bag contents) or flex centroid."""
        if self.body >= 0:
            return d.xpos[self.body].copy()
        return d.flexvert_xpos[self.vert].mean(axis=0)

    def finger_forces(self, d: mujoco.MjData) -> np.ndarray:
        """Normal contact force between each finger and the object [N] (all element faces)."""
        out = np.zeros(self.n_fingers)
        if d.ncon == 0:
            return out
        c = d.contact
        geom, flex, adr = c.geom, c.flex, c.efc_address
        obj = self.object_geom[geom].any(axis=1)
        if self.flex >= 0:
            obj |= (flex == self.flex).any(axis=1)
        fing = np.max(self.geom_finger[geom], axis=1)
        use = obj & (fing >= 0) & (adr >= 0)
        if use.any():
            np.add.at(out, fing[use], d.efc_force[adr[use]])
        return out

    def _vertex_map(self, m: mujoco.MjModel, d0: mujoco.MjData) -> None:
        """The flex's vertex positions as a linear map of its nodes' slide-joint coordinates,
        x = x0 + J (q - q0), so that the edge strain can be read at every step of a chunk from
        the rollout's states. J is probed column by column (exact: slide joints, and
        interpolation weights that are linear in the nodes)."""
        f = self.flex
        nodes = (m.flex_nodebodyid[m.flex_nodeadr[f]:m.flex_nodeadr[f] + m.flex_nodenum[f]]
                 if m.flex_interp[f] else m.flex_vertbodyid[self.vert])
        joints = [j for b in sorted({int(b) for b in nodes})
                  for j in range(m.body_jntadr[b], m.body_jntadr[b] + m.body_jntnum[b])]
        if not joints or any(m.jnt_type[j] != mujoco.mjtJoint.mjJNT_SLIDE for j in joints):
            return  # not a linear map: strain only at chunk ends
        self.q_adr = m.jnt_qposadr[joints]
        self.q0 = d0.qpos[self.q_adr].copy()
        cols = []
        for k in self.q_adr:
            d0.qpos[k] += 1.0e-3
            mujoco.mj_kinematics(m, d0)
            mujoco.mj_flex(m, d0)
            cols.append(((d0.flexvert_xpos[self.vert] - self.rest_verts) / 1.0e-3).ravel())
            d0.qpos[k] -= 1.0e-3
        jac = np.array(cols).T
        jac[np.abs(jac) < 1e-9] = 0.0
        from scipy.sparse import csr_matrix
        self.jac = csr_matrix(jac)
        # state rows start with the time, then qpos (mjSTATE_FULLPHYSICS)
        self.q_col = mujoco.mj_stateSize(m, mujoco.mjtState.mjSTATE_TIME) + self.q_adr

    def edge_strain_steps(self, states: np.ndarray) -> float:
        """Largest tensile edge strain over the rollout ``states`` (n, nstate) [-]."""
        dq = states[:, self.q_col] - self.q0
        x = self.rest_verts.ravel() + (self.jac @ dq.T).T
        x = x.reshape(len(states), -1, 3)
        e = x[:, self.edge_verts[:, 0]] - x[:, self.edge_verts[:, 1]]
        return float(np.max(np.linalg.norm(e, axis=2) / self.edge_length0 - 1.0))

    def _edge_lengths(self, x: np.ndarray) -> np.ndarray:
        return np.linalg.norm(x[self.edge_verts[:, 0]] - x[self.edge_verts[:, 1]], axis=1)

    def edge_strain(self, d: mujoco.MjData) -> float:
        """Largest tensile strain of the object flex's edges against the rest shape [-]."""
        if self.flex < 0:
            return 0.0
        x = d.flexvert_xpos[self.vert]
        return float(np.max(self._edge_lengths(x) / self.edge_length0 - 1.0))


def grasp_height(p: GripperParams, obj: GraspObject, proto: GraspProtocol) -> float:
    """Palm-face height above the floor at which the fingers close [m]."""
    return max(p.finger.length + proto.tip_clearance, obj.height + proto.palm_clearance)


class _Recorder:
    """Accumulates the trial's peaks from the per-step sensor arrays and chunk-end checks."""

    def __init__(self, probe: _Probe):
        self.probe = probe
        self.peak_total = 0.0
        self.peak_finger = np.zeros(probe.n_fingers)
        self.peak_tension = 0.0
        self.peak_strain = 0.0
        self.frame_sink = None  # optional: receives (phase, states, sensordata) of every chunk

    def add(self, sensordata: np.ndarray, d: mujoco.MjData, states: np.ndarray | None = None) -> None:
        """Fold in one chunk: ``sensordata`` and ``states`` (the rollout's rows, one per step) and
        ``d`` at the chunk's end. Contact forces are read at the chunk's end only; flex strain
        at every step where ``states`` is given (see :meth:`_Probe.edge_strain_steps`)."""
        per_finger = self.probe.finger_forces(d)
        self.peak_finger = np.maximum(self.peak_finger, per_finger)
        self.peak_total = max(self.peak_total, float(per_finger.sum()))
        self.peak_tension = max(self.peak_tension, float(sensordata[:, self.probe.tension_adr].max()))
        if self.probe.obj.kind not in STRAIN_DAMAGE_KINDS:
            return
        if states is not None and self.probe.q_adr is not None:
            self.peak_strain = max(self.peak_strain, self.probe.edge_strain_steps(states))
        else:
            self.peak_strain = max(self.peak_strain, self.probe.edge_strain(d))


class _Stepper:
    """Steps one ``MjData`` in open-loop chunks with ``mujoco.rollout`` (no thread pool).

    The rollout object and its output buffers are kept for the whole trial and the wrapper's
    shape checks are skipped (the buffers are built here with the right shapes), so the cost
    per chunk beyond the physics is a few microseconds.
    """

    def __init__(self, m: mujoco.MjModel, d: mujoco.MjData):
        self.m, self.d = m, d
        self.roll = rollout.Rollout(nthread=0)
        self.state0 = np.empty((1, mujoco.mj_stateSize(m, STATE_SPEC)))
        mujoco.mj_getState(m, d, self.state0[0], STATE_SPEC)
        self.warm0 = np.empty((1, m.nv))
        self._out: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self.last_states = self.state0

    def step(self, u: np.ndarray) -> np.ndarray:
        """Apply the controls ``u`` (n, nu) for n steps; return the sensor data (n, nsensordata).

        ``d`` must not be changed between calls: each chunk starts from the previous chunk's
        last state row (the same numbers ``mj_getState`` would read from ``d``).
        """
        n = len(u)
        if n not in self._out:
            self._out[n] = (np.empty((1, n, self.state0.shape[1])), np.empty((1, n, self.m.nsensordata)))
        state, sens = self._out[n]
        self.last_states = state[0]
        # the solver's warm start is not part of the physics state: pass it on so that the
        # result does not depend on where chunks are cut (bitwise equal to plain mj_step)
        self.warm0[0] = self.d.qacc_warmstart
        self.roll.rollout([self.m], [self.d], self.state0, np.ascontiguousarray(u[None]),
                          control_spec=CTRL_SPEC, skip_checks=True, nstep=n,
                          initial_warmstart=self.warm0, state=state, sensordata=sens)
        self.state0[0] = state[0, -1]  # the next chunk's start
        return sens[0]

    def finite(self) -> bool:
        """Whether the last chunk's final state (time, qpos, qvel, act, ...) is finite."""
        return bool(np.isfinite(self.last_states[-1]).all())

    def close(self) -> None:
        self.roll.close()


def _run_phase(stepper, probe, rec, ctrl_fn, duration, chunk, what, on_chunk=None) -> None:
    """Step ``duration`` seconds with controls ``ctrl_fn(t_phase) -> (n, nu)`` in chunks."""
    m, d = stepper.m, stepper.d
    n_total = int(round(duration / m.opt.timestep))
    done = 0
    while done < n_total:
        n = min(chunk, n_total - done)
        t = (done + np.arange(n)) * m.opt.timestep
        sens = stepper.step(ctrl_fn(t))
        done += n
        if not stepper.finite() or d.warning.number.any():
            check_stable(m, d, what)  # raises, naming the warnings
            raise SimulationUnstable(f"{what}: non-finite state at t = {d.time:.4f} s")
        rec.add(sens, d, stepper.last_states)
        if rec.frame_sink is not None:
            rec.frame_sink.add(what, stepper.last_states, sens)
        if on_chunk is not None and on_chunk(d):
            return


def run_trial(obj: str | GraspObject, seed: int = 0, index: int = 0, *,
              params: GripperParams | None = None, protocol: GraspProtocol | None = None,
              noise: TrialNoise | None = None, placement: Placement | None = None,
              frame_sink=None) -> dict:
    """Run one scripted grasp trial; return its record (a JSON-ready dict, SI units).

    ``placement`` overrides the sampled perturbation. ``frame_sink`` (optional, see
    :class:`gripper.video.FrameRecorder`) gets ``start(model, probe)`` once and then
    ``add(phase, states, sensordata)`` after every chunk, for recording a video. An unstable simulation does not raise:
    the record gets ``status = "error"`` and the message, and counts neither as success nor
    failure.
    """
    obj = get_object(obj) if isinstance(obj, str) else obj.validate()
    proto = (protocol or GraspProtocol()).validate()
    p = (params or GripperParams()).validate()
    p = p.replace(sim=p.sim.replace(timestep=proto.timestep)).validate()
    noise = (noise or TrialNoise()).validate()
    place = placement or sample_placement(obj, noise, seed, index)
    record = {
        "trial_id": f"{obj.name}-{seed}-{index:04d}", "object": obj.name, "seed": seed, "index": index,
        "perturbation": {"x_m": place.x, "y_m": place.y, "yaw_rad": place.yaw,
                         "mass_scale": place.mass_scale, "friction_scale": place.friction_scale},
        "config_hash": config_hash(p.to_dict(), proto.to_dict(), noise.to_dict(), obj.to_dict()),
        "versions": versions(),
    }
    wall0 = time.perf_counter()
    m = build_grasp_scene(p, obj, place)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    probe = _Probe(m, obj, p.layout.n_fingers)
    rec = _Recorder(probe)
    if frame_sink is not None:
        frame_sink.start(m, probe)
        rec.frame_sink = frame_sink
    try:
        out = _protocol_steps(m, d, p, obj, proto, probe, rec)
        record.update(status="ok", **out)
    except SimulationUnstable as e:
        record.update(status="error", success=None, failed_phase=None, error=str(e))
    record.update(
        peak_total_force_N=rec.peak_total, peak_finger_force_N=rec.peak_finger.tolist(),
        peak_cable_tension_N=rec.peak_tension, warnings=int(sum(w.number for w in d.warning)),
        sim_time_s=float(d.time), wall_time_s=time.perf_counter() - wall0)
    return record


def _protocol_steps(m, d, p, obj, proto, probe, rec) -> dict:
    stepper = _Stepper(m, d)
    try:
        return _protocol_phases(stepper, p, obj, proto, probe, rec)
    finally:
        stepper.close()


def _protocol_phases(stepper, p, obj, proto, probe, rec) -> dict:
    m, d = stepper.m, stepper.d
    ch = proto.chunk_steps
    z_grasp = grasp_height(p, obj, proto) - p.lift.home_height  # lift_z set-point [m]
    close_cmd = min(obj.close_command * proto.close_command_scale, float(m.actuator_ctrlrange[probe.servo[0], 1]))
    close_rate = proto.close_speed / p.servo.spool_radius  # rad/s of spool

    def ctrl(servo, z, x=None):
        def fn(t):
            u = np.zeros((len(t), m.nu))
            u[:, probe.servo] = np.asarray(servo(t))[:, None] if callable(servo) else servo
            u[:, probe.lift_z] = z(t) if callable(z) else z
            if x is not None:
                u[:, probe.lift_x] = x(t)
            return u
        return fn

    _run_phase(stepper, probe, rec, ctrl(0.0, 0.0), proto.settle_s, ch, "settle")
    start = probe.object_pos(d)
    t_app = abs(z_grasp) / proto.approach_speed
    _run_phase(stepper, probe, rec, ctrl(0.0, lambda t: z_grasp * np.minimum(1.0, t / t_app)), t_app, ch, "approach")
    t_close = close_cmd / close_rate
    _run_phase(stepper, probe, rec, ctrl(lambda t: close_cmd * np.minimum(1.0, t / t_close), z_grasp),
               t_close + proto.close_hold_s, ch, "close")
    t_lift = proto.lift_height / proto.lift_speed
    z_top = z_grasp + proto.lift_height
    lift = ctrl(close_cmd, lambda t: z_grasp + proto.lift_height * np.minimum(1.0, t / t_lift))
    _run_phase(stepper, probe, rec, lift, t_lift + proto.lift_settle_s, ch, "lift")

    def rel(dd):
        return probe.object_pos(dd) - dd.xpos[probe.palm]

    rel_lift = rel(d)
    phase_ok = {}

    def check(name):
        h = probe.object_pos(d)[2] - start[2]
        slip = float(np.linalg.norm(rel(d) - rel_lift))
        phase_ok[name] = (h >= proto.success_height and slip < proto.max_slip, h, slip)

    check("lift")
    max_slip = [0.0]

    def track(dd):
        max_slip[0] = max(max_slip[0], float(np.linalg.norm(rel(dd) - rel_lift)))
        return False

    _run_phase(stepper, probe, rec, ctrl(close_cmd, z_top), proto.hold_s, ch, "hold", track)
    check("hold")
    w = 2 * math.pi * proto.shake_frequency
    _run_phase(stepper, probe, rec, ctrl(close_cmd, z_top, lambda t: proto.shake_amplitude * np.sin(w * t)),
               proto.shake_s, ch, "shake", track)
    check("shake")
    lift_height = float(probe.object_pos(d)[2] - start[2])
    slip = float(np.linalg.norm(rel(d) - rel_lift))
    damage = damage_measure(m, d, obj, probe, peak_strain=rec.peak_strain, peak_force=rec.peak_total)
    if proto.release:
        _run_phase(stepper, probe, rec, ctrl(lambda t: close_cmd * np.maximum(0.0, 1 - t / proto.release_s), z_top),
                   proto.release_s, ch, "release")
    damaged = bool(damage > obj.damage_limit)
    failed = next((name for name in ("lift", "hold", "shake") if not phase_ok[name][0]), None)
    if failed is None and damaged:
        failed = "damage"
    return {
        "success": failed is None, "failed_phase": failed, "lift_height_m": lift_height, "slip_m": slip,
        "max_slip_m": max_slip[0], "damaged": damaged, "damage_measure": damage,
        "damage_limit": obj.damage_limit, "close_command_rad": close_cmd,
    }


def damage_measure(m, d, obj, probe, *, peak_strain: float, peak_force: float) -> float:
    """The object's damage measure: peak edge strain (balloon, bag), permanent dent after
    spring-back (paper box, from the state in ``d``), else the peak contact force [N]."""
    if obj.kind in STRAIN_DAMAGE_KINDS:
        return peak_strain
    if obj.kind == "paper_box":
        return permanent_dent(m, d, probe)
    return peak_force


def permanent_dent(m: mujoco.MjModel, d: mujoco.MjData, probe: _Probe) -> float:
    """Largest permanent deviation of the box shell from its rest shape [m].

    On a copy of the state, contacts and gravity are switched off and the shell springs back
    elastically for :data:`SPRINGBACK_S`; what is left is plastic. The deviation is taken after
    the best rigid fit (Kabsch) of the rest shape, so rigid motion does not count.
    """
    d2 = mujoco.MjData(m)
    mujoco.mj_copyData(d2, m, d)
    saved = m.opt.disableflags
    m.opt.disableflags = saved | int(mujoco.mjtDisableBit.mjDSBL_CONTACT) | int(mujoco.mjtDisableBit.mjDSBL_GRAVITY)
    try:
        d2.ctrl[:] = 0.0
        for _ in range(int(SPRINGBACK_S / m.opt.timestep)):
            mujoco.mj_step(m, d2)
        mujoco.mj_forward(m, d2)
    finally:
        m.opt.disableflags = saved
    return _rigid_fit_residual(probe.rest_verts, d2.flexvert_xpos[probe.vert])


def _rigid_fit_residual(x0: np.ndarray, x: np.ndarray) -> float:
    """Max distance between ``x`` and the best rigid motion of ``x0`` (Kabsch) [m]."""
    c0, c = x0.mean(axis=0), x.mean(axis=0)
    h = (x0 - c0).T @ (x - c)
    u, _, vt = np.linalg.svd(h)
    s = np.eye(3)
    s[2, 2] = np.sign(np.linalg.det(vt.T @ u.T))
    r = vt.T @ s @ u.T
    fitted = (x0 - c0) @ r.T + c
    return float(np.linalg.norm(x - fitted, axis=1).max())


# Pull-out test: load ramp rate [N/s] and the largest load tried [N]. 20 N/s keeps the test
# quasi-static (the grasp's slowest mode, the object swinging in the fingers, is ≈ 5 Hz) and
# reaches the 100 N cap in 5 s.
PULL_RATE = 20.0
PULL_MAX = 100.0
PULL_SLIP = 0.005


def run_pullout(obj: str | GraspObject, *, params: GripperParams | None = None,
                protocol: GraspProtocol | None = None, placement: Placement | None = None,
                rate: float = PULL_RATE, max_force: float = PULL_MAX, slip: float = PULL_SLIP) -> dict:
    """Holding force [N]: grasp and lift as in a trial, then pull the object straight down.

    The pull is a body force on every body of the object in proportion to its mass (as a
    hanging weight would load it), ramped at ``rate`` until the object has moved ``slip``
    relative to the palm; the force at that moment is the holding force. If ``max_force`` is
    reached first, the result is that bound with ``held_at_max = True``.
    """
    obj = get_object(obj) if isinstance(obj, str) else obj.validate()
    proto = (protocol or GraspProtocol()).validate()
    p = (params or GripperParams()).validate()
    p = p.replace(sim=p.sim.replace(timestep=proto.timestep)).validate()
    for name, v in (("rate", rate), ("max_force", max_force), ("slip", slip)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"pullout.{name}: must be > 0, got {v!r}")
    m = build_grasp_scene(p, obj, placement or Placement())
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    probe = _Probe(m, obj, p.layout.n_fingers)
    rec = _Recorder(probe)
    short = proto.replace(hold_s=0.3, shake_s=0.0)
    _protocol_steps(m, d, p, obj, short, probe, rec)
    masses = m.body_mass[probe.object_bodies]
    share = masses / masses.sum()
    rel0 = probe.object_pos(d) - d.xpos[probe.palm]
    u = d.ctrl.copy()
    dt = m.opt.timestep
    force = 0.0
    while force < max_force:
        force = min(max_force, force + rate * dt)
        d.xfrc_applied[probe.object_bodies, 2] = -force * share
        d.ctrl[:] = u
        mujoco.mj_step(m, d)
        check_stable(m, d, "pull-out")
        if np.linalg.norm(probe.object_pos(d) - d.xpos[probe.palm] - rel0) >= slip:
            return {"object": obj.name, "holding_force_N": force, "held_at_max": False,
                    "slip_m": slip, "rate_N_per_s": rate}
    return {"object": obj.name, "holding_force_N": max_force, "held_at_max": True,
            "slip_m": slip, "rate_N_per_s": rate}
