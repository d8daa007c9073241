"""A uniform elastic beam as a hinge chain, and the exact elastica it must reproduce.

This fixes the mapping the whole package uses between a continuous bending stiffness EI [N·m²]
and hinge springs: a beam of length L cut into N cells of length h = L/N becomes N hinges of
stiffness ``k = EI / h`` placed at the cell centres, i.e. links of length h/2, h, ..., h, h/2
(the midpoint rule: each hinge carries the curvature of the cell around it). The tip error of
this chain against the exact elastica falls as 1/N².

The finger itself concentrates its compliance in the bridges under the cuts, so there the hinges
sit at the cuts (see :mod:`gripper.model.builders`); for a bridge of length l and second moment I the same
rule gives ``k = E I / l``.

Example:
    >>> tip = elastica_tip_moment(m_l_over_ei=1.0, length=0.1)
    >>> chain = chain_tip_position("moment", 1.0, n=10, length=0.1, ei=1e-3)
    >>> float(np.linalg.norm(chain - tip)) < 0.01 * 0.1
    True
"""

from __future__ import annotations

import math
from typing import Literal

import mujoco
import numpy as np
from scipy.integrate import solve_bvp
from scipy.optimize import root

LoadKind = Literal["moment", "force"]


def hinge_stiffness_for_beam(ei: float, length: float, n: int) -> float:
    """Hinge stiffness [N·m/rad] of an ``n``-hinge chain standing for a beam of ``ei`` [N·m²]."""
    return ei * n / length


def elastica_tip_moment(m_l_over_ei: float, length: float) -> np.ndarray:
    """Exact tip (x, y) [m] of a cantilever under a pure end moment: a circular arc."""
    if m_l_over_ei == 0:
        return np.array([length, 0.0])
    radius = length / m_l_over_ei
    return np.array([radius * math.sin(m_l_over_ei), radius * (1.0 - math.cos(m_l_over_ei))])


def elastica_tip_force(f_l2_over_ei: float, length: float) -> np.ndarray:
    """Exact tip (x, y) [m] of a cantilever under a tip dead load perpendicular to its root axis.

    Solves the elastica theta'' = -(F/EI) cos(theta), theta(0) = 0, theta'(L) = 0 as a boundary
    value problem (scipy ``solve_bvp``), then integrates the shape.
    """
    a = f_l2_over_ei
    s = np.linspace(0.0, 1.0, 401)  # s in units of L

    def rhs(s, y):  # y = (theta, theta', x, y)
        return np.vstack([y[1], -a * np.cos(y[0]), np.cos(y[0]), np.sin(y[0])])

    def bc(ya, yb):
        return np.array([ya[0], yb[1], ya[2], ya[3]])

    guess = np.zeros((4, s.size))
    guess[0] = 0.5 * a * (2 * s - s**2) * min(1.0, 1.4 / max(a, 1e-9))
    guess[2] = s
    sol = solve_bvp(rhs, bc, s, guess, tol=1e-10, max_nodes=100_000)
    if not sol.success:
        raise RuntimeError(f"elastica BVP did not converge: {sol.message}")
    return np.array([sol.y[2, -1], sol.y[3, -1]]) * length


def beam_chain_model(n: int, length: float, ei: float) -> mujoco.MjModel:
    """Planar chain (x along the beam, bending about z) of ``n`` hinges, midpoint placement."""
    h = length / n
    k = hinge_stiffness_for_beam(ei, length, n)
    spec = mujoco.MjSpec()
    spec.option.gravity = [0, 0, 0]
    spec.compiler.degree = False
    body = spec.worldbody.add_body(name="link0")
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[h / 4, 0.002, 0.002], pos=[h / 4, 0, 0],
                  mass=1e-3)
    x_next = h / 2
    for i in range(1, n + 1):
        link_len = h if i < n else h / 2
        child = body.add_body(name=f"link{i}", pos=[x_next if i == 1 else h, 0, 0])
        child.add_joint(name=f"hinge{i}", type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1],
                        stiffness=[k, 0, 0])
        child.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[link_len / 2, 0.002, 0.002],
                       pos=[link_len / 2, 0, 0], mass=1e-3)
        body = child
    body.add_site(name="tip", pos=[h / 2, 0, 0])
    return spec.compile()


def _generalized_load(model, data, kind: LoadKind, magnitude: float) -> np.ndarray:
    """Generalised force of the external load at the current configuration."""
    tip = model.site("tip").id
    body = model.site_bodyid[tip]
    qfrc = np.zeros(model.nv)
    force = np.array([0.0, magnitude, 0.0]) if kind == "force" else np.zeros(3)
    torque = np.array([0.0, 0.0, magnitude]) if kind == "moment" else np.zeros(3)
    mujoco.mj_applyFT(model, data, force, torque, data.site_xpos[tip], body, qfrc)
    return qfrc


def chain_tip_position(kind: LoadKind, load: float, *, n: int, length: float,
                       ei: float) -> np.ndarray:
    """Static tip (x, y) [m] of the hinge chain under ``load``.

    ``load`` is M·L/EI for ``kind="moment"`` or F·L²/EI (dead load along +y) for ``"force"``.
    The equilibrium ``spring forces + load = 0`` is found with MuJoCo evaluating the springs,
    kinematics and load Jacobian, and scipy's root finder stepping the load up in increments.
    """
    model = beam_chain_model(n, length, ei)
    data = mujoco.MjData(model)
    scale = ei / length if kind == "moment" else ei / length**2
    q = np.zeros(model.nq)

    def residual(qpos, magnitude):
        data.qpos[:] = qpos
        mujoco.mj_fwdPosition(model, data)
        mujoco.mj_fwdVelocity(model, data)  # fills qfrc_passive (springs)
        return data.qfrc_passive + _generalized_load(model, data, kind, magnitude)

    for frac in np.linspace(0.05, 1.0, 20):
        sol = root(residual, q, args=(frac * load * scale,), method="hybr", tol=1e-12)
        if not sol.success:
            sol = root(residual, q, args=(frac * load * scale,), method="lm", tol=1e-14)
        if not sol.success or np.abs(residual(sol.x, frac * load * scale)).max() > 1e-9 * scale:
            raise RuntimeError(f"chain equilibrium failed at {frac:.1f} of the load: {sol.message}")
        q = sol.x
    data.qpos[:] = q
    mujoco.mj_kinematics(model, data)
    return data.site_xpos[model.site("tip").id][:2].copy()
