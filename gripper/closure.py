"""The closed cut: how a hinge resists closing past the angle where its cut's faces meet.

Past the closure angle the two silicone teeth on either side of a cut press on each other. The
default model (``springs.closure = "teeth"``) treats that as a rotational spring of stiffness
``K_c`` beyond the closure angle, estimated from the finger's own geometry and modulus, and
realises it with the hinge's MuJoCo joint limit: a soft limit of time constant ``tau``, damping
ratio 1 and impedance ``d`` holds a static load as a spring of stiffness

    K = 1 / ((1 - d) · tau² · A),

``A`` the limit's inverse inertia (``dof_invweight0``): the limit force f balances the load
when R·f = aref, R = (1-d)/d·A, aref = -d·k·r, k = 1/(d·tau)² (MuJoCo's soft-constraint
definitions; R is diagonal, so this holds whichever other limits are active). Solving for tau
gives each hinge's ``solref``. The stiffness is a property of the silicone, so it does not
change with the time step, and neither do grasp results (``scripts/bench_speed.py``, README
"Time step").

Teeth estimate (:func:`teeth_closure_stiffness`): an extra closure dθ moves the cut's faces
together by dθ·s at height s above the hinge axis. The tooth material between two cuts,
thickness t(z) = pitch - 2·(z - bridge)·tan(cut/2) at height z, is squeezed across its
thickness; each hinge owns half of each neighbouring tooth, two halves in series of total
thickness t, so the face pressure is E·dθ·s/t and the moment about the hinge

    K_c = E · width · ∫ (z - z_hinge)² / t(z) dz,   z from the bridge top to the grasping face.

Uniaxial, linear, small strain, faces in full contact: for the default design 1.7 N·m/rad, 16×
the bridge's own spring (paper 000: 0.109 N·m/rad). It leaves out the silicone's stiffening at
large compression (the Yeoh fit stiffens) and the faces' gradual contact from the grasping
face down (softer at first), so it is good to a factor of about two; ``closure="stiffness"``
takes a measured value.

Example:
    >>> from gripper.params import GripperParams
    >>> from gripper.closure import teeth_closure_stiffness
    >>> p = GripperParams()
    >>> round(teeth_closure_stiffness(p.finger, p.material), 2)
    1.72
"""

from __future__ import annotations

import math
import warnings

import mujoco
import numpy as np
from scipy.integrate import quad

from gripper.params import DEG, FingerGeometry, GripperParams, Material

# Shortest limit time constant, in time steps, for every closure model: four steps held the
# stiffest stable stop under random commands (see gripper.model._add_defaults).
MIN_STEPS = 4.0
# Impedance of the hinge limits (solimp d0 = dwidth: constant over the violation).
HINGE_LIMIT_IMPEDANCE = 0.9995


def teeth_closure_stiffness(g: FingerGeometry, material: Material) -> float:
    """Rotational stiffness of a closed cut from compressing its two teeth [N·m/rad].

    See the module docstring for the model and its limits.
    """
    half_tan = math.tan(0.5 * g.cut_angle_deg * DEG)

    def integrand(z: float) -> float:
        tooth = g.pitch - 2.0 * (z - g.bridge_thickness) * half_tan
        return (z - g.hinge_z) ** 2 / tooth

    integral, _ = quad(integrand, g.bridge_thickness, g.height)
    return material.youngs_modulus * g.width * integral


def closure_stiffness(p: GripperParams) -> float | None:
    """The closed-cut stiffness the model realises [N·m/rad]; ``None`` for the rigid stop."""
    if p.springs.closure == "rigid":
        return None
    if p.springs.closure == "stiffness":
        return p.springs.closure_stiffness
    return teeth_closure_stiffness(p.finger, p.material)


def closure_time_constants(p: GripperParams, inv_weight: np.ndarray) -> np.ndarray:
    """Limit time constants [s] of hinges with inverse inertias ``inv_weight`` [1/(kg·m²)].

    Rigid: ``MIN_STEPS`` time steps. Compliant: the tau that makes the limit a spring of the
    closure stiffness, but never below ``MIN_STEPS`` steps; where that floor binds, the stop is
    softer than asked and a warning says so.
    """
    floor = MIN_STEPS * p.sim.timestep
    k = closure_stiffness(p)
    if k is None:
        return np.full(len(inv_weight), floor)
    d = HINGE_LIMIT_IMPEDANCE
    tau = 1.0 / np.sqrt((1.0 - d) * k * np.asarray(inv_weight, dtype=float))
    if np.any(tau < floor):
        warnings.warn(
            f"springs.closure: a closed-cut stiffness of {k:.3g} N·m/rad needs limit time "
            f"constants down to {tau.min():.2e} s, below {MIN_STEPS:g} time steps "
            f"({floor:.2e} s); those hinges get the {MIN_STEPS:g}-step stop (softer)",
            stacklevel=3)
    return np.maximum(tau, floor)


def tune_closure_limits(spec: mujoco.MjSpec, p: GripperParams, model: mujoco.MjModel) -> None:
    """Set each hinge limit's ``solref`` from the closure model; ``model`` is ``spec`` compiled
    (for the inverse inertias). Edits ``spec`` in place."""
    hinges = [j for j in spec.joints if j.type == mujoco.mjtJoint.mjJNT_HINGE and "_hinge" in j.name]
    if not hinges:
        return
    inv_w = np.array([model.dof_invweight0[model.jnt_dofadr[model.joint(j.name).id]] for j in hinges])
    for j, tau in zip(hinges, closure_time_constants(p, inv_w), strict=True):
        j.solref_limit = [round(float(tau), 6), 1.0]
