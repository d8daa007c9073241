"""The paper's bending test on one finger: cable shortening rate r against bending.

Paper 000 §IV runs the actuator for 2 s at a 5e-4 s step while the cable is pulled in. Here the
servo's position set-point is ramped so that the commanded cable shortening rate
``r = (cable reeled in) / (cable length in the straight finger)`` rises linearly from 0 to
``r_max`` over ``duration``; the recorded ``r`` is the one measured on the reel. The
quasi-static mode holds each of ``n_points`` set-points until the finger is at rest.

Example:
    >>> from gripper.experiments.bending import BendingConfig, run_bending_test
    >>> res = run_bending_test(BendingConfig(r_max=0.2))
    >>> bool(res.bending_angle_deg[-1] > 30)
    True
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.drives.cable.finger import build_bending_spec
from gripper.experiments.protocol import BendingConfig
from gripper.parts.names import FingerNames
from gripper.sim.stability import SimulationUnstable, check_stable


@dataclass
class BendingResult:
    """Arrays of a bending test, one row per sample (SI units unless the name says deg).

    Attributes:
        t: time [s], shape (n,).
        r: measured cable shortening rate [-], shape (n,).
        r_command: commanded cable shortening rate [-], shape (n,).
        tension_N: cable tension [N], shape (n,).
        joint_angles_deg: hinge angles M2..Mn [deg], shape (n, n_hinges).
        bending_angle_deg: angle from the base element's axis to the tip element's axis [deg].
        tip_xyz_m: tip position (neutral axis at the distal face) in the clamp frame [m].
        spring_moment_Nm: k (theta - theta_rest) per hinge [N·m], shape (n, n_hinges).
        cable_moment_Nm: tension × cable lever arm per hinge [N·m], shape (n, n_hinges).
        limit_active: hinge at its joint limit (constraint active), shape (n, n_hinges).
        warnings: MuJoCo warning counts over the run.
        wall_time_s: wall-clock time of the simulation loop [s].
    """

    t: np.ndarray
    r: np.ndarray
    r_command: np.ndarray
    tension_N: np.ndarray
    joint_angles_deg: np.ndarray
    bending_angle_deg: np.ndarray
    tip_xyz_m: np.ndarray
    spring_moment_Nm: np.ndarray
    cable_moment_Nm: np.ndarray
    limit_active: np.ndarray
    warnings: int
    wall_time_s: float
    config: BendingConfig = field(default_factory=BendingConfig)

    def to_json_dict(self) -> dict:
        """JSON-ready dict with the arrays the CLI prints (``gripper bend --json``)."""
        return {
            "mode": self.config.mode,
            "config": asdict(self.config),
            "t": self.t.tolist(),
            "r": self.r.tolist(),
            "r_command": self.r_command.tolist(),
            "tension_N": self.tension_N.tolist(),
            "joint_angles_deg": self.joint_angles_deg.tolist(),
            "bending_angle_deg": self.bending_angle_deg.tolist(),
            "tip_xyz_m": self.tip_xyz_m.tolist(),
            "warnings": self.warnings,
            "wall_time_s": self.wall_time_s,
        }


class _Probe:
    """Reads one finger's state out of MjData."""

    def __init__(self, model: mujoco.MjModel, p: GripperParams):
        self.m = model
        self.names = FingerNames("f0", p.finger.n_segments)
        self.hinge_qpos = np.array([model.joint(h).qposadr[0] for h in self.names.hinges])
        self.hinge_dof = np.array([model.joint(h).dofadr[0] for h in self.names.hinges])
        self.hinge_ids = np.array([model.joint(h).id for h in self.names.hinges])
        self.reel_qpos = model.joint(self.names.reel).qposadr[0]
        self.reel_dof = model.joint(self.names.reel).dofadr[0]
        self.tension = model.sensor(f"{self.names.cable}_tension").adr[0]
        self.tip_site = model.site(self.names.tip).id
        self.cable_id = model.tendon(self.names.cable).id
        self.base_body = model.body(self.names.bodies[0]).id
        self.stiffness = model.jnt_stiffness[self.hinge_ids].copy()
        self.springref = model.qpos_spring[self.hinge_qpos].copy()
        self.cable_length0 = p.finger.length

    def read(self, d: mujoco.MjData) -> tuple:
        q = d.qpos[self.hinge_qpos]
        r = d.qpos[self.reel_qpos] / self.cable_length0
        tension = d.sensordata[self.tension]
        base_R = d.xmat[self.base_body].reshape(3, 3)
        tip = base_R.T @ (d.site_xpos[self.tip_site] - d.xpos[self.base_body])
        ten_j = _cable_jacobian(self.m, d, self.cable_id)[self.hinge_dof]
        cable_moment = -tension * ten_j
        spring_moment = self.stiffness * (q - self.springref)
        at_limit = np.zeros(len(q), dtype=bool)
        for i in range(d.nefc):
            if d.efc_type[i] == mujoco.mjtConstraint.mjCNSTR_LIMIT_JOINT:
                at_limit |= self.hinge_ids == d.efc_id[i]
        return q, r, tension, tip, spring_moment, cable_moment, at_limit


def _cable_jacobian(m: mujoco.MjModel, d: mujoco.MjData, tendon_id: int) -> np.ndarray:
    """Row ``tendon_id`` of the tendon Jacobian, dense (MuJoCo stores it sparse in sparse models)."""
    if mujoco.mj_isSparse(m):
        adr, nnz = m.ten_J_rowadr[tendon_id], m.ten_J_rownnz[tendon_id]
        row = np.zeros(m.nv)
        row[m.ten_J_colind[adr:adr + nnz]] = d.ten_J[adr:adr + nnz]
        return row
    return d.ten_J.reshape(m.ntendon, m.nv)[tendon_id]


def run_bending_test(config: BendingConfig | None = None,
                     params: GripperParams | None = None, on_sample=None) -> BendingResult:
    """Run the bending test and return the recorded arrays.

    ``on_sample(model, data)``, if given, is called at every recorded sample (after the
    row is taken), e.g. to keep states for pictures.

    Raises:
        ValueError: invalid config or parameters.
        SimulationUnstable: MuJoCo warned or the state became non-finite.
    """
    cfg = (config or BendingConfig()).validate()
    p = (params or GripperParams()).validate()
    model = build_bending_spec(p, timestep=cfg.timestep).compile()
    data = mujoco.MjData(model)
    probe = _Probe(model, p)
    servo = model.actuator(probe.names.servo).id
    theta_per_r = probe.cable_length0 * model.actuator_gear[servo, 0]  # spool angle per unit r
    ctrl_max = model.actuator_ctrlrange[servo, 1]
    if cfg.r_max * theta_per_r > ctrl_max:
        raise ValueError(f"bend.r_max: the servo's travel allows r <= "
                         f"{ctrl_max / theta_per_r:.3f} with this spool, got {cfg.r_max!r}")
    mujoco.mj_forward(model, data)

    run = _BendingRun(model, data, probe, servo, theta_per_r, on_sample)
    t0 = time.perf_counter()
    if cfg.mode == "dynamic":
        run.ramp(cfg)
    else:
        run.quasi_static(cfg)
    wall = time.perf_counter() - t0
    check_stable(model, data, "bending test")
    return _bending_result(run.rows, data, wall, cfg)


@dataclass
class _BendingRun:
    """The bending scene being run: the servo's set-point is ``r`` x ``theta_per_r`` [rad], and
    each sample is a row of ``rows`` (time [s], commanded r, then :meth:`_Probe.read`)."""

    model: mujoco.MjModel
    data: mujoco.MjData
    probe: _Probe
    servo: int
    theta_per_r: float  # spool angle per unit r [rad]
    on_sample: Callable[[mujoco.MjModel, mujoco.MjData], object] | None
    rows: list[tuple] = field(default_factory=list)

    def sample(self, r_cmd: float) -> None:
        """Record a row at the current state (then ``on_sample``)."""
        mujoco.mj_forward(self.model, self.data)
        self.rows.append((self.data.time, r_cmd, *self.probe.read(self.data)))
        if self.on_sample is not None:
            self.on_sample(self.model, self.data)

    def ramp(self, cfg: BendingConfig) -> None:
        """Dynamic mode: r ramped from 0 to ``r_max`` over ``duration`` [s], ``n_points``
        samples evenly spaced in time."""
        model, data = self.model, self.data
        n_steps = int(round(cfg.duration / cfg.timestep))
        record_at = set(np.linspace(0, n_steps, cfg.n_points).round().astype(int).tolist())
        for step in range(n_steps + 1):
            r_cmd = cfg.r_max * min(1.0, data.time / cfg.duration)
            if step in record_at:
                self.sample(r_cmd)
            data.ctrl[self.servo] = r_cmd * self.theta_per_r
            mujoco.mj_step(model, data)
            if step % 200 == 0:
                check_stable(model, data, "bending test")

    def quasi_static(self, cfg: BendingConfig) -> None:
        """Quasi-static mode: each of ``n_points`` set-points from 0 to ``r_max`` held until the
        finger is at rest, then sampled."""
        for r_cmd in np.linspace(0.0, cfg.r_max, cfg.n_points):
            self.data.ctrl[self.servo] = r_cmd * self.theta_per_r
            self._settle(cfg, r_cmd)
            self.sample(r_cmd)

    def _settle(self, cfg: BendingConfig, r_cmd: float) -> None:
        """Step in blocks of 50 until the hinges and reel are still (``settle_tol``) or swing
        within ``settle_band_deg``, after at least 0.05 s.

        Raises:
            SimulationUnstable: no rest within ``settle_time_max`` [s], or an unstable state.
        """
        model, data, probe = self.model, self.data, self.probe
        dofs = probe.hinge_dof
        t_start = data.time
        qadr = model.jnt_qposadr[model.dof_jntid[dofs]]
        while True:
            lo = hi = data.qpos[qadr].copy()
            for _ in range(50):
                mujoco.mj_step(model, data)
                lo, hi = np.minimum(lo, data.qpos[qadr]), np.maximum(hi, data.qpos[qadr])
            check_stable(model, data, "bending test (quasi-static)")
            reel_v = data.qvel[probe.reel_dof] / probe.cable_length0
            at_rest = (max(np.abs(data.qvel[dofs]).max(), abs(reel_v)) < cfg.settle_tol
                       or np.degrees(hi - lo).max() < cfg.settle_band_deg)
            if at_rest and data.time - t_start > 0.05:
                break
            if data.time - t_start > cfg.settle_time_max:
                raise SimulationUnstable(
                    f"bending test: no rest within {cfg.settle_time_max} s at r = {r_cmd:.3f}")


def _bending_result(rows: list[tuple], data: mujoco.MjData, wall: float, cfg: BendingConfig
                    ) -> BendingResult:
    """The recorded rows as arrays (see :class:`BendingResult`)."""
    cols = list(zip(*rows, strict=True))
    q = np.array(cols[2])
    return BendingResult(
        t=np.array(cols[0]),
        r=np.array(cols[3]),
        r_command=np.array(cols[1]),
        tension_N=np.array(cols[4]),
        joint_angles_deg=np.degrees(q),
        bending_angle_deg=np.degrees(q.sum(axis=1)),
        tip_xyz_m=np.array(cols[5]),
        spring_moment_Nm=np.array(cols[6]),
        cable_moment_Nm=np.array(cols[7]),
        limit_active=np.array(cols[8]),
        warnings=int(sum(w.number for w in data.warning)),
        wall_time_s=wall,
        config=cfg,
    )
