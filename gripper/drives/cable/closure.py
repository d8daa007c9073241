"""The closed cut: how a hinge resists closing past the angle where its cut's faces meet.

The default model (``springs.closure = "teeth"``) gives each hinge, past its closure angle, the
moment of the two silicone teeth either side of the cut squeezed as a neo-Hookean solid, from
the finger's geometry and modulus, realised as the hinge's MuJoCo joint limit (its impedance
curve and a per-hinge time constant), and matches it to the design under the trials'
integrator. The derivation and its checks: ``docs/model.md``, "The closed cut".

Example:
    >>> from gripper.core.params import GripperParams
    >>> from gripper.drives.cable.closure import teeth_closure_stiffness
    >>> p = GripperParams()
    >>> round(teeth_closure_stiffness(p.finger, p.material), 2)   # N·m/rad, the 1.9 mm bridge
    2.25
"""

from __future__ import annotations

import copy
import functools
import math
import warnings

import mujoco
import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq, least_squares

from gripper.core.params import DEG, FingerGeometry, GripperParams, Material
from gripper.parts.defaults import HINGE_LIMIT_IMPEDANCE, MIN_STEPS, RIGID_STOP_SOLIMP

# Impedance range of the teeth's stiffening stop: d0 sets the softest, d1 (MuJoCo's cap) the
# stiffest; G(d1)/G(d0) = 5.0 with G(d) = d²/(1-d) (see the module docstring for why not 10).
TEETH_IMPEDANCE = (HINGE_LIMIT_IMPEDANCE, 0.9999)
# Strain at which a tooth counts as squashed flat (the neo-Hookean stress diverges at 1).
MAX_TOOTH_STRAIN = 0.999


def _tooth(g: FingerGeometry):
    half_tan = math.tan(0.5 * g.cut_angle_deg * DEG)
    return lambda z: g.pitch - 2.0 * (z - g.bridge_thickness) * half_tan


def teeth_closure_stiffness(g: FingerGeometry, material: Material) -> float:
    """Small-overrun rotational stiffness of a closed cut, K_c = E·w·∫ s²/t dz [N·m/rad]."""
    tooth = _tooth(g)
    integral, _ = quad(lambda z: (z - g.hinge_z) ** 2 / tooth(z), g.bridge_thickness, g.height)
    return material.youngs_modulus * g.width * integral


def teeth_moment(g: FingerGeometry, material: Material, overrun: float) -> float:
    """Moment of the squeezed neo-Hookean teeth at ``overrun`` past closure [N·m] (overrun [rad])."""
    if overrun <= 0.0:
        return 0.0
    tooth = _tooth(g)
    mu = material.youngs_modulus / 3.0

    def integrand(z: float) -> float:
        s = z - g.hinge_z
        lam = 1.0 - min(overrun * s / tooth(z), MAX_TOOTH_STRAIN)
        return mu * (lam ** -2 - lam) * s

    moment, _ = quad(integrand, g.bridge_thickness, g.height, limit=200)
    return g.width * moment


def teeth_lock_angle(g: FingerGeometry) -> float:
    """Overrun past closure at which the first point of a tooth is squashed flat, min t/s [rad]
    (12.4° for the default design, at the grasping face). The model's hinges stop rigidly there
    (:func:`gripper.drives.cable.finger.add_finger`)."""
    z = np.linspace(g.bridge_thickness, g.height, 401)[1:]
    return float(np.min(_tooth(g)(z) / (z - g.hinge_z)))


def _g(d):
    return d * d / (1.0 - d)


def _sigmoid(x, mid: float, power: float):
    """MuJoCo's impedance shape y(x) on [0, 1] (XML reference, solimp)."""
    x = np.clip(x, 0.0, 1.0)
    a, b = mid ** (1.0 - power), (1.0 - mid) ** (1.0 - power)
    return np.where(x <= mid, a * x ** power, 1.0 - b * (1.0 - x) ** power)


@functools.lru_cache(maxsize=64)
def teeth_impedance(g: FingerGeometry, material: Material) -> tuple[float, float, float, float, float]:
    """The hinge limits' ``solimp`` (d0, d1, width [rad], midpoint, power) whose secant
    stiffness follows the teeth's M(θ)/θ, relative to its value at zero overrun."""
    d0, d1 = TEETH_IMPEDANCE
    k0 = teeth_closure_stiffness(g, material)
    top = _g(d1) / _g(d0)
    lock = teeth_lock_angle(g)  # the secant stiffness passes any bound below it
    width = brentq(lambda th: teeth_moment(g, material, th) / (th * k0) - top, 1e-4 * lock, lock)
    theta = np.linspace(width / 50, width, 50)
    ratio = np.array([teeth_moment(g, material, th) / (th * k0) for th in theta])
    d_target = np.array([brentq(lambda d, r=r: _g(d) - r * _g(d0), d0, d1) for r in np.minimum(ratio, top)])
    y_target = (d_target - d0) / (d1 - d0)
    fit = least_squares(lambda q: _sigmoid(theta / width, q[0], q[1]) - y_target, [0.5, 2.0],
                        bounds=([0.01, 1.0], [0.99, 10.0]))
    mid, power = (float(v) for v in fit.x)
    return d0, d1, float(width), mid, power


def closure_stiffness(p: GripperParams) -> float | None:
    """The closed-cut stiffness at zero overrun [N·m/rad]; ``None`` for the rigid stop."""
    if p.springs.closure == "rigid":
        return None
    if p.springs.closure == "stiffness":
        return p.springs.closure_stiffness
    return teeth_closure_stiffness(p.finger, p.material)


def closure_impedance(p: GripperParams) -> tuple[float, float, float, float, float]:
    """The hinge limits' ``solimp``: the teeth's stiffening curve, or constant for the others."""
    if p.springs.closure == "teeth":
        return teeth_impedance(p.finger, p.material)
    return RIGID_STOP_SOLIMP


def realised_secant_stiffness(p: GripperParams, overrun) -> np.ndarray:
    """Secant stiffness M/θ the MuJoCo limit realises at ``overrun`` [rad], [N·m/rad] (compliant
    closures only): K_c times G(d(θ))/G(d(0)), G(d) = d²/(1-d)."""
    k0 = closure_stiffness(p)
    if k0 is None:
        raise ValueError("springs.closure: the rigid stop has no stiffness of its own")
    d0, d1, width, mid, power = closure_impedance(p)
    d = d0 + (d1 - d0) * _sigmoid(np.abs(np.asarray(overrun, dtype=float)) / width, mid, power)
    return k0 * _g(d) / _g(d0)


def closure_time_constants(p: GripperParams, inv_weight: np.ndarray) -> np.ndarray:
    """Limit time constants [s] of hinges with inverse inertias ``inv_weight`` [1/(kg·m²)].

    Rigid: ``MIN_STEPS`` time steps. Compliant: the tau that gives the closure stiffness at zero
    overrun, tau = (d0/d1)/sqrt((1-d0)·A·K_c), but never below ``MIN_STEPS`` steps; where that
    floor binds, the stop is softer than asked and a warning says so.
    """
    floor = MIN_STEPS * p.sim.timestep
    k = closure_stiffness(p)
    if k is None:
        return np.full(len(inv_weight), floor)
    d0, d1 = closure_impedance(p)[:2]
    tau = (d0 / d1) / np.sqrt((1.0 - d0) * k * np.asarray(inv_weight, dtype=float))
    if np.any(tau < floor):
        warnings.warn(
            f"springs.closure: a closed-cut stiffness of {k:.3g} N·m/rad needs limit time "
            f"constants down to {tau.min():.2e} s, below {MIN_STEPS:g} time steps "
            f"({floor:.2e} s); those hinges get the {MIN_STEPS:g}-step stop (softer)",
            stacklevel=3)
    return np.maximum(tau, floor)


def tune_closure_limits(spec: mujoco.MjSpec, p: GripperParams, model: mujoco.MjModel) -> None:
    """Set each hinge limit's ``solref`` and ``solimp`` from the closure model; ``model`` is
    ``spec`` compiled (for the inverse inertias). Edits ``spec`` in place."""
    hinges = [j for j in spec.joints if j.type == mujoco.mjtJoint.mjJNT_HINGE and "_hinge" in j.name]
    if not hinges:
        return
    ids = np.array([model.joint(j.name).id for j in hinges])
    inv_w = model.dof_invweight0[model.jnt_dofadr[ids]]
    solimp = [round(v, 6) for v in closure_impedance(p)]
    taus = [round(float(tau), 6) for tau in closure_time_constants(p, inv_w)]
    if p.springs.closure != "rigid" and model.opt.integrator == mujoco.mjtIntegrator.mjINT_DISCRETE:
        tuned = copy.copy(model)  # the spec compiled with the values set below
        tuned.jnt_solref[ids, 0] = taus
        tuned.jnt_solimp[ids] = solimp
        taus = [round(float(tau), 6) for tau in match_discrete_closure(tuned, p, ids)]
    for j, tau in zip(hinges, taus, strict=True):
        j.solref_limit = [tau, 1.0]
        j.solimp_limit = solimp


# Overrun past closure at which the discrete integrator's closed cuts are matched to their design
# [rad]: the match then holds within 0.3° from 2° to 7° (default design; its lock is 8.9° past closure).
MATCH_OVERRUN = 6.0 * DEG
MATCH_TOLERANCE = 0.05 * DEG  # rad
MATCH_SETTLE = 1.0  # s of simulated time to rest (the slowest hinge is at rest within 1e-6 rad/s)


def closed_cut_rest_overrun(model: mujoco.MjModel, p: GripperParams, ids: np.ndarray,
                            overrun: float) -> np.ndarray:
    """Overrun past closure [rad] at which each hinge comes to rest under the moment that, by
    design, holds it ``overrun`` past closure (spring plus closed cut), applied to the hinge
    alone; gravity and contact off, so every hinge carries just its own moment."""
    m = copy.copy(model)
    m.opt.gravity[:] = 0.0
    m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
    d = mujoco.MjData(m)
    closure = m.jnt_range[ids, 1]
    d.qpos[m.jnt_qposadr[ids]] = closure
    design = float(realised_secant_stiffness(p, overrun)) * overrun
    full = m.jnt_stiffness[ids] * (closure - m.qpos_spring[m.jnt_qposadr[ids]] + overrun) + design
    # The moment is ramped in over the first half of the settle (a half-cosine): a step made the
    # lightly damped calibrated hinges (the distal one's fitted damper is 3e-5 N·m·s/rad) ring
    # into the lock 12.4° past closure and the settle went unstable. The rest is the same.
    n = int(round(MATCH_SETTLE / m.opt.timestep))
    for i in range(n):
        ramp = 0.5 * (1.0 - math.cos(math.pi * min(1.0, 2.0 * i / n)))
        d.qfrc_applied[m.jnt_dofadr[ids]] = ramp * full
        mujoco.mj_step(m, d)
    if not np.isfinite(d.qpos).all() or any(w.number for w in d.warning):
        raise RuntimeError("closure: the static match of the closed cuts went unstable")
    return d.qpos[m.jnt_qposadr[ids]] - closure


def match_discrete_closure(model: mujoco.MjModel, p: GripperParams, ids: np.ndarray,
                           iterations: int = 6) -> np.ndarray:
    """Limit time constants [s] that make the closed cuts of hinges ``ids`` hold their designed
    moment under the ``discrete`` integrator.

    The limit-spring formula of the module docstring is what the integrators that size a limit
    with ``dof_invweight0`` realise (``implicitfast``: a hinge held 6° past closure by its design
    moment rests at 5.98°). The discrete integrator sizes the limit in its own effective metric,
    which adds the step times the hinge's damping and spring: the same limit then rested at
    5.3° (0.5 ms) to 3.3° (2 ms) on the distal hinge, 1.8 times too stiff. So, for that
    integrator, each hinge's time constant is scaled by sqrt(designed / reached overrun) (the
    stop's stiffness goes as 1/tau²) until every hinge rests within 0.05° of ``MATCH_OVERRUN``;
    the impedance curve is kept, and with it the stiffening (checked at 2° and 7°: within 0.3°;
    at 8°, within a degree of the default design's lock, 1.4° off).
    Edits ``model``'s ``jnt_solref`` and returns the time constants.
    """
    for _ in range(iterations):
        reached = closed_cut_rest_overrun(model, p, ids, MATCH_OVERRUN)
        if np.abs(reached - MATCH_OVERRUN).max() < MATCH_TOLERANCE:
            break
        if (reached <= 0.0).any():
            raise RuntimeError("closure: a closed cut did not move past closure in the static match")
        # never below the stability floor of closure_time_constants (MIN_STEPS steps)
        model.jnt_solref[ids, 0] = np.maximum(model.jnt_solref[ids, 0] * np.sqrt(MATCH_OVERRUN / reached),
                                              MIN_STEPS * model.opt.timestep)
    return model.jnt_solref[ids, 0].copy()
