"""Fit the hinge-and-spring finger to a bending record (reference run or bench data).

The hinge model (one finger of :func:`gripper.drives.cable.finger.add_finger`, the same parameters) is driven
by the record's cable tension through a tendon force on the same cable path (guide, one via per
element, knot at the tip), so the fit compares like with like: per-element angles and the tip
point at equal tension. Free parameters, in log space and bounded: the stiffness of every hinge
and, when the record has a transient, the damping of every hinge.

Residuals: element angles in units of ``angle_sigma_deg`` and tip x, z in units of
``tip_sigma_m``, at every sample (transient records) or at the static points. A transient fit
also runs the finger to rest at each static point's tension and compares it with the record
near rest there (``FitConfig.static_weight``): the transient alone cannot tell a soft, heavily
damped hinge from a stiffer one, and a calibration must get the finger at rest right. Runs to
rest use a model of their own (``STATIC_STEP``). The samples of the ``held_out`` load levels
are left out of the fit and scored afterwards.

Solver: :func:`mujoco.minimize.least_squares` (Levenberg-Marquardt with box bounds). Each
residual evaluation is one batched :func:`mujoco.rollout.rollout` over one model per parameter
point, so the finite-difference Jacobian runs on MuJoCo's thread pool. ``mujoco.sysid`` was not
used: its parameter and residual plumbing assumes sensor-matched trajectories of one model,
whereas here the residual is computed from derived quantities (angles summed along the chain).

Example:
    >>> from gripper.calibration.fit import fit_hinges
    >>> from gripper.references.continuum import run_reference
    >>> fit = fit_hinges(run_reference())          # doctest: +SKIP
    >>> fit.stiffness                               # doctest: +SKIP
"""

from __future__ import annotations

import copy
import io
import math
import os
import time
from dataclasses import dataclass, field

import mujoco
import mujoco.rollout
import numpy as np
from mujoco import minimize

from gripper.core.fields import Validated
from gripper.core.params import GripperParams
from gripper.drives.cable.finger import add_element_meshes, add_finger
from gripper.parts.defaults import add_defaults, set_options
from gripper.parts.names import FingerNames
from gripper.references.continuum import BendingRecord

# Static runs (the finger at rest at each static point's tension) use their own model: the
# discrete integrator, implicit in the hinge springs, at a 0.05 s step, where each step acts
# nearly as a Newton step towards equilibrium, with damping tau*K per hinge. Measured on the
# fitted default finger at 0.15 N: within 0.02° of rest after 50 steps, 0.001° after 100. The
# old runs, 0.4 s holds at the record's 5e-4 s step with c = 0.02 s x K, were far from rest for
# soft hinges (the finger rang for seconds: 67° after 0.5 s, 74.2° at rest).
STATIC_STEP = 0.05  # s
STATIC_HOLD_STEPS = 100  # steps per static point
STATIC_SETTLE_TAU = 0.1  # s, damping over stiffness of the static runs


@dataclass(frozen=True)
class FitConfig(Validated):
    """Settings of the hinge fit.

    Attributes:
        fit_damping: also fit per-hinge damping (needs a record with a transient) [-].
        held_out: indices of the static points (load levels) left out of the fit [-].
            Default (2,): the middle of five levels. Distinct indices >= 0; checked against
            the record's levels by :func:`check_held_out` (``gripper calibrate`` does so before
            the reference run).
        angle_sigma_deg: scale of the angle residuals [deg] (1°: a protractor on a bench).
        tip_sigma_m: scale of the tip residuals [m] (1 mm).
        stiffness_bounds: bounds of each hinge stiffness [N·m/rad].
        damping_bounds: bounds of each hinge damping [N·m·s/rad].
        max_iter: iteration cap of the least-squares solver [-].
        static_weight: weight of the settled static response in a transient fit [-]: the
            hinge model is also run to rest at each static point's tension (damping
            ``STATIC_SETTLE_TAU`` x stiffness) and its angles and tip there, against the
            record's mean over the last quarter of that hold, join the residual. At 1
            (default) each mean weighs as much as the samples it averages (the least-squares
            weight of a mean of noisy samples), so the static block counts a quarter of each
            hold. Without it the transient alone left stiffness and damping trading off: the
            fit matched the 2 s record (tip RMS 0.9 %) with springs so soft and damped that
            the hinge finger, once at rest, bent 88° at 0.15 N where the reference bends 74°.
            0 turns the block off.
    """

    fit_damping: bool = True
    held_out: tuple[int, ...] = (2,)
    angle_sigma_deg: float = 1.0
    tip_sigma_m: float = 1.0e-3
    # Upper bound 1 N·m/rad: about 9x paper 000's 1.9e-3 N·m/deg (0.109 N·m/rad, Table 2), far
    # above any plausible bridge. With 10 N·m/rad the search tried 62 points whose stiff spring
    # made the lightest hinge mode unstable at the 5e-4 s step; they were rejected (DIVERGED) but
    # each printed a MuJoCo warning. The fit itself is the same to 7 digits.
    stiffness_bounds: tuple[float, float] = (1.0e-4, 1.0)
    damping_bounds: tuple[float, float] = (1.0e-7, 1.0)
    max_iter: int = 60
    static_weight: float = 1.0

    def validate(self) -> FitConfig:
        for name in ("angle_sigma_deg", "tip_sigma_m"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"fit.{name}: must be > 0, got {v!r}")
        # the range, duplicates and what remains to fit: check_held_out, against the levels
        if not (isinstance(self.held_out, tuple | list) and all(map(_is_index, self.held_out))):
            raise ValueError(f"--held-out (fit.held_out): must be a list of load level indices "
                             f"(integers from 0), got {self.held_out!r}")
        if not (math.isfinite(self.static_weight) and self.static_weight >= 0):
            raise ValueError(f"fit.static_weight: must be >= 0, got {self.static_weight!r}")
        for name in ("stiffness_bounds", "damping_bounds"):
            lo, hi = getattr(self, name)
            if not (0 < lo < hi and math.isfinite(hi)):
                raise ValueError(f"fit.{name}: need 0 < low < high, got {(lo, hi)!r}")
        return self


def _is_index(v: object) -> bool:
    return isinstance(v, int | np.integer) and not isinstance(v, bool)


def check_held_out(held_out, n_levels: int, *, min_fit_levels: int = 1) -> set[int]:
    """The held-out level indices as a set, checked against a record of ``n_levels`` static
    points (load levels): each in ``0..n_levels - 1``, none twice, and at least
    ``min_fit_levels`` levels left to fit.

    Raises:
        ValueError: one line naming ``--held-out`` and the allowed range.
    """
    most = n_levels - min_fit_levels
    if most <= 0:
        allowed = (f"allowed: none (the fit needs all {n_levels} load level"
                   f"{'s' if n_levels != 1 else ''}; give --held-out '')")
    else:
        allowed = (f"allowed: distinct levels in 0..{n_levels - 1} ({n_levels} load levels), at "
                   f"most {most} of them, leaving at least {min_fit_levels} to fit")
    held = list(held_out)
    for v in held:
        if not _is_index(v) or not 0 <= v < n_levels:
            raise ValueError(f"--held-out: level {v!r} does not exist; {allowed}")
    for v in held:
        if held.count(v) > 1:
            raise ValueError(f"--held-out: level {v} is given twice; {allowed}")
    if len(held) > max(most, 0):
        raise ValueError(f"--held-out: {len(held)} of {n_levels} levels held out leaves "
                         f"{n_levels - len(held)} to fit, fewer than {min_fit_levels}; {allowed}")
    return set(int(v) for v in held)


def min_fit_levels(record: BendingRecord, n_params: int) -> int:
    """Static points a static fit of ``n_params`` parameters needs: enough finite observables
    (element angles B2..Bn and tip x, z) for as many residuals as parameters."""
    idx = record.static
    if not len(idx):
        return 1
    per_row = (np.isfinite(record.element_angles_deg[idx, 1:]).sum(axis=1)
               + np.isfinite(record.tip_xz_m[idx]).sum(axis=1))
    least = int(per_row.min())
    return max(1, math.ceil(n_params / least)) if least > 0 else len(idx) + 1


# A fitted value within this fraction of a bound is "at the bound": the solver clamps a
# parameter that wants to leave the box exactly onto it (mujoco.minimize, in log space).
BOUND_RTOL = 1.0e-6


def bound_warnings(stiffness: np.ndarray, damping: np.ndarray | None, cfg: FitConfig
                   ) -> list[str]:
    """One line per quantity and bound that fitted hinges ended at (see ``BOUND_RTOL``):
    such a value is the box's, not the data's (a spring the data ask to be softer or stiffer
    than the bounds allow: wrong units, a wrong tension, or a finger that does not fit the
    hinge model). ``damping`` None: not fitted."""
    out = []
    items = [("stiffness", "N·m/rad", stiffness, cfg.stiffness_bounds, "stiffness_bounds",
              ("softer", "stiffer"))]
    if damping is not None:
        items.append(("damping", "N·m·s/rad", damping, cfg.damping_bounds, "damping_bounds",
                      ("less damped", "more damped")))
    for what, unit, values, (lo, hi), name, wants in items:
        for side, bound, want in (("lower", lo, wants[0]), ("upper", hi, wants[1])):
            at = [j for j, v in enumerate(values) if abs(float(v) - bound) <= BOUND_RTOL * bound]
            if at:
                hinges = ", ".join(f"B{j + 1}-B{j + 2}" for j in at)
                out.append(f"fit: {what} of hinge{'s' if len(at) > 1 else ''} {hinges} ended at "
                           f"the {side} bound {bound:g} {unit} (fit.{name}): the data ask for a "
                           f"hinge {want} than the bounds allow; the value is the bound's, not "
                           f"the data's: check the data's units and tensions")
    return out


@dataclass
class FitResult:
    """Fitted hinge parameters and how well they reproduce the record.

    Attributes:
        stiffness: per-hinge stiffness [N·m/rad].
        damping: per-hinge damping [N·m·s/rad].
        rest_angle_deg: per-hinge rest angle [deg] (not fitted: 0, moulded straight).
        fitted: the hinge model's record at the fitted values.
        metrics: fit quality (see :func:`fit_metrics`), plus ``diverged_trial_points``: parameter
            points of the search whose run diverged and was rejected, and ``warnings``: one
            line per fitted quantity that ended at a bound (:func:`bound_warnings`).
        iterations: solver iterations.
        wall_time_s: fit wall time [s].
    """

    stiffness: np.ndarray
    damping: np.ndarray
    rest_angle_deg: np.ndarray
    fitted: BendingRecord
    metrics: dict
    iterations: int
    wall_time_s: float
    config: FitConfig = field(default_factory=FitConfig)


def build_hinge_finger(p: GripperParams, timestep: float, *, static: bool = False
                       ) -> tuple[mujoco.MjModel, FingerNames]:
    """One hinge finger in its own frame, its cable pulled by a tendon force (ctrl = tension).

    Gravity is off, as in the reference (see :mod:`gripper.references.continuum`). ``static``:
    the discrete integrator (implicit in the springs) for runs to rest, see ``STATIC_STEP``.
    """
    spec = mujoco.MjSpec()
    set_options(spec, p.replace(sim=p.sim.replace(gravity=0.0)))
    spec.option.timestep = timestep  # STATIC_STEP is beyond sim.timestep's range: runs to rest only
    spec.option.integrator = (mujoco.mjtIntegrator.mjINT_DISCRETE if static
                              else mujoco.mjtIntegrator.mjINT_IMPLICITFAST)
    spec.modelname = "finger_calibration"
    defaults = add_defaults(spec, p)
    add_element_meshes(spec, p)
    names = add_finger(spec, spec.worldbody, p, "f0", [0, 0, 0], [1, 0, 0, 0], defaults)
    ten = spec.add_tendon(name=names.cable, width=0.5 * p.cable.diameter)
    ten.wrap_site(names.cable_guide)
    for j in range(1, p.finger.n_segments + 1):
        ten.wrap_site(names.cable_site(j))
    ten.wrap_site(names.tip_anchor)
    act = spec.add_actuator(name="tension", target=names.cable,
                            trntype=mujoco.mjtTrn.mjTRN_TENDON)
    act.gear = [-1.0, 0, 0, 0, 0, 0]  # positive control pulls: tension [N]
    S = mujoco.mjtSensor
    for h in names.hinges:
        spec.add_sensor(name=h, type=S.mjSENS_JOINTPOS, objname=h,
                        objtype=mujoco.mjtObj.mjOBJ_JOINT)
    spec.add_sensor(name="tip", type=S.mjSENS_FRAMEPOS, objname=names.tip,
                    objtype=mujoco.mjtObj.mjOBJ_SITE)
    spec.add_sensor(name="cable_length", type=S.mjSENS_TENDONPOS, objname=names.cable,
                    objtype=mujoco.mjtObj.mjOBJ_TENDON)
    return spec.compile(), names


class HingeSimulator:
    """Runs the hinge finger under a tension history for many parameter points at once."""

    def __init__(self, p: GripperParams, timestep: float):
        self.p = p
        self.model, self.names = build_hinge_finger(p, timestep)
        self.static_model, _ = build_hinge_finger(p, STATIC_STEP, static=True)
        self.n_hinges = p.finger.n_hinges
        self.jnt = np.array([self.model.joint(h).id for h in self.names.hinges])
        self.dof = self.model.jnt_dofadr[self.jnt]
        self.nthread = max(1, min(os.cpu_count() or 1, 8))
        self.datas = [mujoco.MjData(self.model) for _ in range(self.nthread)]
        self.static_datas = [mujoco.MjData(self.static_model) for _ in range(self.nthread)]
        d = self.datas[0]
        mujoco.mj_forward(self.model, d)
        self.length0 = float(d.sensordata[-1])
        self.diverged = 0  # parameter points whose run diverged (rejected by the search)
        self.state0 = np.empty(mujoco.mj_stateSize(self.model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
        mujoco.mj_getState(self.model, d, self.state0, mujoco.mjtState.mjSTATE_FULLPHYSICS)

    def run(self, stiffness: np.ndarray, damping: np.ndarray, tension: np.ndarray,
            sample: np.ndarray, *, static: bool = False
            ) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """Element angles [deg], tip x, z [m] and r at steps ``sample`` for each column.

        ``stiffness``/``damping``: shape (n_hinges, k). ``tension``: per step [N].
        ``static``: step the static model (``STATIC_STEP``) instead of the record's.
        """
        k = stiffness.shape[1]
        base = self.static_model if static else self.model
        datas = self.static_datas if static else self.datas
        models = []
        for i in range(k):
            m = copy.copy(base)
            m.jnt_stiffness[self.jnt] = stiffness[:, i]
            m.dof_damping[self.dof] = damping[:, i]
            models.append(m)
        ctrl = np.asarray(tension, dtype=float).reshape(1, -1, 1)
        state, sens = mujoco.rollout.rollout(models, datas[:max(1, min(k, self.nthread))],
                                             self.state0, ctrl, skip_checks=False)
        out = []
        nh = self.n_hinges
        for i in range(k):
            s = sens[i][sample]
            # MuJoCo resets a diverging simulation to its initial state: the clock jumps back.
            if not np.isfinite(s).all() or np.any(np.diff(state[i][:, 0]) <= 0):
                s = np.full_like(s, DIVERGED)  # a huge residual: the solver steps away
                self.diverged += 1
            q = s[:, :nh]
            angles = np.degrees(np.hstack([np.zeros((len(s), 1)), np.cumsum(q, axis=1)]))
            tip = s[:, [nh, nh + 2]]
            r = (self.length0 - s[:, nh + 3]) / self.p.finger.length
            out.append((angles, tip, r))
        return out


DIVERGED = 1.0e3  # value given to every output of a diverged trial point [rad, m]


def _history(record: BendingRecord, timestep: float, static_only: bool
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tension per step, the step index of each record sample, and the samples used."""
    if not static_only:
        steps = np.rint(record.t / timestep).astype(int)
        grid = np.arange(steps[-1] + 1) * timestep
        tension = np.interp(grid, record.t, record.tension_N)
        return tension, steps, np.arange(len(record.t))
    # Static points only: a staircase through the recorded tensions, each held
    # STATIC_HOLD_STEPS steps of the static model.
    idx = record.static
    n_hold = STATIC_HOLD_STEPS
    levels = record.tension_N[idx]
    tension = np.repeat(levels, n_hold)
    steps = np.arange(1, len(idx) + 1) * n_hold - 1
    full = np.full(len(record.t), -1)
    full[idx] = steps
    return tension, full, idx


@dataclass
class _Targets:
    """One block of the fit's residuals: what the hinge model is compared with at each sample.

    Attributes:
        angles: element angles B2..Bn from B1 [deg], 0 where not observed.
        tip: tip x, z [m], 0 where not observed.
        angles_ok: which of ``angles`` are observed (bench data may lack one).
        tip_ok: which of ``tip`` are observed.
        weight: weight of the block's residuals [-]: a number, or one per residual.
    """

    angles: np.ndarray
    tip: np.ndarray
    angles_ok: np.ndarray
    tip_ok: np.ndarray
    weight: float | np.ndarray = 1.0

    @classmethod
    def observed(cls, angles: np.ndarray, tip: np.ndarray, weight: float | np.ndarray = 1.0
                 ) -> _Targets:
        """Targets from observations that are NaN where missing."""
        angles_ok, tip_ok = np.isfinite(angles), np.isfinite(tip)
        return cls(np.nan_to_num(angles), np.nan_to_num(tip), angles_ok, tip_ok, weight)

    def residuals(self, runs, cfg: FitConfig) -> np.ndarray:
        """Scaled misfit of each run of :meth:`HingeSimulator.run`: one column per run."""
        cols = []
        for ang, tip, _ in runs:
            ra = np.where(self.angles_ok, ang[:, 1:] - self.angles, 0.0) / cfg.angle_sigma_deg
            rt = np.where(self.tip_ok, tip - self.tip, 0.0) / cfg.tip_sigma_m
            cols.append(self.weight * np.hstack([ra, rt]).ravel())  # row-major: per sample
        return np.array(cols).T


@dataclass
class _SettledBlock:
    """The settled static block of a transient fit (see ``FitConfig.static_weight``): the
    static model's tension staircase [N], the steps of its fitted static points and their
    targets at rest."""

    tension: np.ndarray
    steps: np.ndarray
    targets: _Targets


def _settled_block(record: BendingRecord, cfg: FitConfig, held: set[int], timestep: float,
                   n_hinges: int) -> _SettledBlock | None:
    """The settled static block of a fit of ``record``; None where the fit has none (a static
    fit, ``static_weight`` 0 or every static point held out)."""
    static_fit = np.array([int(record.static[i]) for i in range(len(record.static))
                           if i not in held], dtype=int)
    if not (cfg.fit_damping and cfg.static_weight > 0 and len(static_fit) > 0):
        return None
    s_tension, s_step, _ = _history(record, timestep, True)
    s_ang, s_tip, s_count = _settled_targets(record, static_fit)
    # Each target is a mean of s_count samples: weight sqrt(count) gives it the weight of
    # those samples (least squares with the noise of a mean).
    s_weight = cfg.static_weight * np.sqrt(np.repeat(s_count, n_hinges + 2))
    return _SettledBlock(s_tension, s_step[static_fit], _Targets.observed(s_ang, s_tip, s_weight))


def _unpack(x: np.ndarray, n_hinges: int, cfg: FitConfig) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness [N·m/rad] and damping [N·m·s/rad] per hinge from the log parameters ``x``
    (damping ``STATIC_SETTLE_TAU`` x stiffness when it is not fitted)."""
    k = np.exp(x[:n_hinges])
    c = np.exp(x[n_hinges:]) if cfg.fit_damping else STATIC_SETTLE_TAU * k
    return k, c


@dataclass
class _Residual:
    """The fit's residual as a function of the log parameters: one column per parameter point
    (``x`` of shape (n_par, k)), or a vector for a single point."""

    sim: HingeSimulator
    cfg: FitConfig
    n_par: int
    tension: np.ndarray  # per step of the fit's model [N]
    steps: np.ndarray  # step of each fitted sample
    targets: _Targets
    static_only: bool
    settled: _SettledBlock | None

    def __call__(self, x: np.ndarray) -> np.ndarray:
        x2 = x.reshape(self.n_par, -1)
        nh = self.sim.n_hinges
        ks, cs = zip(*(_unpack(x2[:, j], nh, self.cfg) for j in range(x2.shape[1])), strict=True)
        ks, cs = np.array(ks).T, np.array(cs).T
        runs = self.sim.run(ks, cs, self.tension, self.steps, static=self.static_only)
        res = self.targets.residuals(runs, self.cfg)
        if self.settled is not None:
            s = self.settled
            runs = self.sim.run(ks, STATIC_SETTLE_TAU * ks, s.tension, s.steps, static=True)
            res = np.vstack([res, s.targets.residuals(runs, self.cfg)])
        return res if x.ndim == 2 else res[:, 0]


def _fit_samples(record: BendingRecord, cfg: FitConfig, used: np.ndarray, n_par: int,
                 static_only: bool) -> tuple[set[int], np.ndarray]:
    """The held-out static points (checked) and the samples the fit uses: ``used`` less the
    held-out hold windows.

    Raises:
        ValueError: bad held-out levels, or fewer residuals than ``n_par`` parameters.
    """
    held = check_held_out(cfg.held_out, len(record.static),
                          min_fit_levels=min_fit_levels(record, n_par) if static_only else 1)
    held_windows = _held_out_mask(record, held)
    fit_samples = np.array([i for i in used if not held_windows[i]], dtype=int)
    n_obs = (np.isfinite(record.element_angles_deg[fit_samples, 1:]).sum()
             + np.isfinite(record.tip_xz_m[fit_samples]).sum())
    n_res = int(n_obs)
    if n_res < n_par:
        raise ValueError(f"data: {len(fit_samples)} usable points give {n_res} residuals, "
                         f"fewer than the {n_par} parameters to fit")
    return held, fit_samples


def _start_and_bounds(record: BendingRecord, p: GripperParams, cfg: FitConfig
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The solver's start point and box (log parameters: stiffness, then damping if fitted)."""
    nh = p.finger.n_hinges
    k0 = _initial_stiffness(record, p)
    lo_k, hi_k = cfg.stiffness_bounds
    k0 = np.clip(k0, lo_k * 1.01, hi_k * 0.99)
    x0 = np.log(k0)
    lower, upper = np.full(nh, math.log(lo_k)), np.full(nh, math.log(hi_k))
    if cfg.fit_damping:
        c0 = np.clip(0.02 * k0, cfg.damping_bounds[0] * 1.01, cfg.damping_bounds[1] * 0.99)
        x0 = np.concatenate([x0, np.log(c0)])
        lower = np.concatenate([lower, np.full(nh, math.log(cfg.damping_bounds[0]))])
        upper = np.concatenate([upper, np.full(nh, math.log(cfg.damping_bounds[1]))])
    return x0, lower, upper


def _fitted_metrics(sim: HingeSimulator, k: np.ndarray, c: np.ndarray, record: BendingRecord,
                    p: GripperParams, cfg: FitConfig, held: set[int], timestep: float
                    ) -> tuple[BendingRecord, dict]:
    """The hinge model's record at the fitted values and its metrics (see :class:`FitResult`)."""
    static_only = not cfg.fit_damping
    fitted = simulate_record(sim, k, c, record, timestep, static_only)
    metrics = fit_metrics(record, fitted, p, held)
    settled = (fitted if static_only else
               simulate_record(sim, k, STATIC_SETTLE_TAU * k, record, timestep, True))
    metrics["settled"] = settled_metrics(record, settled, p)
    # diverged trial points (each also printed a MuJoCo warning): a count, so that a user with
    # wider bounds sees why the console filled with warnings while the fit still converged
    metrics["diverged_trial_points"] = sim.diverged
    # fitted values at their bounds: one line each, stored with the calibration and printed by
    # gripper calibrate ("warning: ...")
    metrics["warnings"] = bound_warnings(k, c if cfg.fit_damping else None, cfg)
    return fitted, metrics


def fit_hinges(record: BendingRecord, params: GripperParams | None = None,
               config: FitConfig | None = None, *, timestep: float = 5.0e-4) -> FitResult:
    """Fit per-hinge stiffness (and damping) to ``record`` (see the module docstring).

    Raises:
        ValueError: a record too small for the number of parameters, or bad settings.
    """
    p = (params or GripperParams()).validate()
    cfg = (config or FitConfig()).validate()
    nh = p.finger.n_hinges
    if record.element_angles_deg.shape[1] != p.finger.n_segments:
        raise ValueError(f"record: has {record.element_angles_deg.shape[1]} elements, the "
                         f"design has {p.finger.n_segments}")
    static_only = not cfg.fit_damping
    sim = HingeSimulator(p, timestep)
    tension, step_of_sample, used = _history(record, timestep, static_only)
    n_par = nh * (2 if cfg.fit_damping else 1)
    held, fit_samples = _fit_samples(record, cfg, used, n_par, static_only)
    target_ang = (record.element_angles_deg - record.element_angles_deg[:, :1])[fit_samples, 1:]
    targets = _Targets.observed(target_ang, record.tip_xz_m[fit_samples])
    residual = _Residual(sim, cfg, n_par, tension, step_of_sample[fit_samples], targets,
                         static_only, _settled_block(record, cfg, held, timestep, nh))
    x0, lower, upper = _start_and_bounds(record, p, cfg)
    t0 = time.perf_counter()
    x, trace = minimize.least_squares(x0, residual, bounds=(lower, upper), max_iter=cfg.max_iter,
                                      verbose=0, output=io.StringIO())
    wall = time.perf_counter() - t0
    k, c = _unpack(x, nh, cfg)
    fitted, metrics = _fitted_metrics(sim, k, c, record, p, cfg, held, timestep)
    return FitResult(stiffness=k, damping=c, rest_angle_deg=np.zeros(nh), fitted=fitted,
                     metrics=metrics, iterations=len(trace), wall_time_s=wall, config=cfg)


def _settled_targets(record: BendingRecord, static_idx: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Angles (B2..Bn, from B1) and tip of the record at rest at each static sample, and the
    weight of each (as many samples as the last quarter of its hold).

    A record with its static points at rest (``record.has_rest``: the reference relaxed each
    hold's end until its own residual was small) gives those. Otherwise (older records) the
    mean over the last quarter of the hold stands in for rest, which it is not where the
    finger still rings at the end of its hold."""
    rel = record.element_angles_deg - record.element_angles_deg[:, :1]
    bounds = np.concatenate([[-1], record.static])
    ang, tip, count = [], [], []
    for j in static_idx:
        level = int(np.searchsorted(record.static, j))
        prev = bounds[level]
        lo = j - max(0, (j - prev) // 4)
        if record.has_rest:
            assert record.rest_element_angles_deg is not None and record.rest_tip_xz_m is not None
            rest = record.rest_element_angles_deg[level]
            ang.append(rest[1:] - rest[0])
            tip.append(record.rest_tip_xz_m[level])
        else:
            ang.append(np.nanmean(rel[lo:j + 1, 1:], axis=0))
            tip.append(np.nanmean(record.tip_xz_m[lo:j + 1], axis=0))
        count.append(j + 1 - lo)
    return np.array(ang), np.array(tip), np.array(count, dtype=float)


def _held_out_mask(record: BendingRecord, held: set[int]) -> np.ndarray:
    """Samples inside the hold windows of the held-out static points."""
    mask = np.zeros(len(record.t), dtype=bool)
    bounds = np.concatenate([[-1], record.static])
    for i in held:
        mask[bounds[i] + 1:bounds[i + 1] + 1] = True
    return mask


def _initial_stiffness(record: BendingRecord, p: GripperParams) -> np.ndarray:
    """Statics at the highest static point: K = T·arm / hinge angle (arm: hole above hinge)."""
    i = record.static[-1] if len(record.static) else len(record.t) - 1
    hinge = np.diff(record.element_angles_deg[i])
    arm = p.finger.hole_height - p.finger.hinge_z
    with np.errstate(divide="ignore"):
        k = record.tension_N[i] * arm / np.radians(np.maximum(hinge, 0.5))
    return np.where(np.isfinite(k), k, 0.1)


def simulate_record(sim: HingeSimulator, k: np.ndarray, c: np.ndarray, record: BendingRecord,
                    timestep: float, static_only: bool) -> BendingRecord:
    """The hinge model's record under ``record``'s tension history."""
    tension, step_of_sample, used = _history(record, timestep, static_only)
    t0 = time.perf_counter()
    (ang, tip, r), = sim.run(k[:, None], c[:, None], tension, step_of_sample[used],
                             static=static_only)
    wall = time.perf_counter() - t0
    n = len(record.t)
    full_ang = np.full((n, ang.shape[1]), np.nan)
    full_tip = np.full((n, 2), np.nan)
    full_r = np.full(n, np.nan)
    full_ang[used], full_tip[used], full_r[used] = ang, tip, r
    return BendingRecord(t=record.t.copy(), tension_N=record.tension_N.copy(), r=full_r,
                         element_angles_deg=full_ang, tip_xz_m=full_tip,
                         static=record.static.copy(), wall_time_s=wall)


def _static_point_error(record: BendingRecord, model: BendingRecord, i: int,
                        length: float, *, at_rest: bool = False) -> dict:
    """Static point ``i`` of ``record`` against ``model`` there: tension, tip error as a
    fraction of ``length`` and relative error of the bending angle (None where not finite).
    ``at_rest``: against the record's static point at rest where it has one."""
    j = int(record.static[i])
    if at_rest and record.has_rest:
        assert record.rest_element_angles_deg is not None and record.rest_tip_xz_m is not None
        ref_tip, ref_ang = record.rest_tip_xz_m[i], record.rest_element_angles_deg[i]
    else:
        ref_tip, ref_ang = record.tip_xz_m[j], record.element_angles_deg[j]
    tip_err = float(np.linalg.norm(model.tip_xz_m[j] - ref_tip))
    bend_ref = float(ref_ang[-1] - ref_ang[0])
    bend_err = abs(float(model.element_angles_deg[j, -1]) - bend_ref) / max(abs(bend_ref), 1e-9)
    return {"level": i, "tension_N": float(record.tension_N[j]),
            "tip_error_frac": tip_err / length if math.isfinite(tip_err) else None,
            "bending_error_frac": bend_err if math.isfinite(bend_err) else None}


def settled_metrics(record: BendingRecord, settled: BendingRecord, p: GripperParams) -> dict:
    """The fitted hinge finger at rest at each static point's tension, against the record there
    (at rest too, where the record has its rest points: equilibrium against equilibrium).

    Keys: ``tip_rms_frac`` (of the finger length) over all static points, and ``levels`` with,
    per point, the tension, the tip error as a fraction of the finger length and the relative
    error of the bending angle. For a reference record this is the calibrated model's static
    accuracy, whatever the transient fit did with the damping.
    """
    levels = [_static_point_error(record, settled, i, p.finger.length, at_rest=True)
              for i in range(len(record.static))]
    tips = [lv["tip_error_frac"] for lv in levels if lv["tip_error_frac"] is not None]
    return {"tip_rms_frac": math.sqrt(sum(t * t for t in tips) / len(tips)) if tips else None,
            "levels": levels}


def fit_metrics(record: BendingRecord, fitted: BendingRecord, p: GripperParams,
                held: set[int]) -> dict:
    """RMS errors of the fitted model against the record.

    Keys: ``tip_rms_m`` and ``tip_rms_frac`` (of the finger length) and ``angle_rms_deg``
    (per element B2..Bn) over the fitted samples; ``held_out`` with, per held-out static
    point, the tip error as a fraction of the finger length and the relative error of the
    bending angle.
    """
    mask = _held_out_mask(record, held) | ~np.isfinite(fitted.tip_xz_m[:, 0])
    fit_idx = np.flatnonzero(~mask)
    ref_ang = record.element_angles_deg - record.element_angles_deg[:, :1]
    da = fitted.element_angles_deg[fit_idx, 1:] - ref_ang[fit_idx, 1:]
    dt = np.linalg.norm(fitted.tip_xz_m[fit_idx] - record.tip_xz_m[fit_idx], axis=1)
    L = p.finger.length
    with np.errstate(invalid="ignore"):
        tip_rms = float(np.sqrt(np.nanmean(dt ** 2))) if np.isfinite(dt).any() else None
        ang_rms = (np.sqrt(np.nanmean(da ** 2, axis=0)).tolist()
                   if np.isfinite(da).any() else None)
    out: dict[str, object] = {
        "samples": int(len(fit_idx)),
        "tip_rms_m": tip_rms,
        "tip_rms_frac": tip_rms / L if tip_rms is not None else None,
        "angle_rms_deg": ang_rms,
        "held_out": [],
    }
    out["held_out"] = [_static_point_error(record, fitted, i, L) for i in sorted(held)]
    return out
