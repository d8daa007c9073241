"""Damage measures of grasped objects: peak edge strain, permanent dent, peak contact force."""

from __future__ import annotations

import mujoco
import numpy as np

from gripper.sim.probes import STRAIN_DAMAGE_KINDS, ObjectProbe

# Elastic spring-back before measuring a permanent dent: contacts and gravity off, this long [s];
# the paper box's slowest wall mode (≈ 30 Hz) and its Rayleigh damping settle well within it.
SPRINGBACK_S = 0.3


def damage_measure(m, d, obj, probe, *, peak_strain: float, peak_force: float) -> float:
    """The object's damage measure: peak edge strain (balloon, bag), permanent dent after
    spring-back (paper box, from the state in ``d``), else the peak contact force [N]."""
    if obj.kind in STRAIN_DAMAGE_KINDS:
        return peak_strain
    if obj.kind == "paper_box":
        return permanent_dent(m, d, probe)
    return peak_force


def running_damage_measure(m, d, obj, probe, *, peak_strain: float, total_force: float) -> float:
    """The damage measure where it must be read at every step (the environment): as
    :func:`damage_measure`, except that the paper box, whose permanent dent needs a spring-back
    simulation, counts any plastic bending of its card (a crease) as damage, which is stricter:
    twice the limit once any plastic strain exists, else 0."""
    if obj.kind == "paper_box":
        a = m.flex_plasticadr[probe.flex]
        crease = float(np.abs(d.plastic[a:]).max()) if d.plastic.size else 0.0
        return obj.damage_limit * 2.0 if crease > 0.0 else 0.0
    if obj.kind in STRAIN_DAMAGE_KINDS:
        return peak_strain
    return total_force


def permanent_dent(m: mujoco.MjModel, d: mujoco.MjData, probe: ObjectProbe) -> float:
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
    return rigid_fit_residual(probe.rest_verts, d2.flexvert_xpos[probe.vert])


def rigid_fit_residual(x0: np.ndarray, x: np.ndarray) -> float:
    """Max distance between ``x`` and the best rigid motion of ``x0`` (Kabsch) [m]."""
    c0, c = x0.mean(axis=0), x.mean(axis=0)
    h = (x0 - c0).T @ (x - c)
    u, _, vt = np.linalg.svd(h)
    s = np.eye(3)
    s[2, 2] = np.sign(np.linalg.det(vt.T @ u.T))
    r = vt.T @ s @ u.T
    fitted = (x0 - c0) @ r.T + c
    return float(np.linalg.norm(x - fitted, axis=1).max())
