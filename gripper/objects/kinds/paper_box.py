"""A closed card box: a 2D flex shell with bending plasticity, damaged by the permanent dent
left after it springs back.

The shell is closed (lid on, as a product box): MuJoCo's flexcomp "box" shell is open at the
top, and its free rim creased under light grasps (4 of 50 default trials dented 2.1-3.5 mm at
3-8 N), which a closed carton's top face prevents.
"""

from __future__ import annotations

from typing import ClassVar

import mujoco
import numpy as np

from gripper.objects.kinds.base import PERMANENT_DENT, Criterion, object_friction
from gripper.objects.kinds.flex import DeformableKind, shell_flex

# Rayleigh damping time [s] of the card: damps the shell's high modes at the 1 ms step.
PAPER_BOX_DAMPING = 0.001
# Paperboard Poisson ratio (0.2-0.4 in-plane).
PAPER_POISSON = 0.3
# Elastic spring-back before measuring a permanent dent: contacts and gravity off, this long [s];
# the paper box's slowest wall mode (≈ 30 Hz) and its Rayleigh damping settle well within it.
SPRINGBACK_S = 0.3


class PaperBox(DeformableKind):
    name = "paper_box"
    criteria: ClassVar[dict[str, Criterion]] = {"dent": PERMANENT_DENT}
    own_criterion = "dent"
    material_fields = ("youngs_modulus", "thickness", "yield_strain")
    # 5 x 5 x 6 points (10 x 10 x 12 mm spacing, 114 vertices); 4 x 4 x 5 would halve its cost and
    # keep the benchmark's outcomes, but its faces are 23-53 % stiffer under a finger
    # (docs/performance.md, "Mesh resolution")
    default_mesh_points = (5, 5, 6)
    square_footprint = True

    def build(self, spec, obj, place, pos, quat, *, rigid_contact):
        # full dofs: bending plasticity needs a non-interpolated 2D flex
        flex = shell_flex(spec, obj, mass=obj.mass * place.mass_scale, pos=pos, quat=quat, radius=0.001,
                          poisson=PAPER_POISSON, damping=PAPER_BOX_DAMPING, rgba=[0.78, 0.65, 0.45, 1.0],
                          friction=object_friction(obj, place))
        flex.stressyield = [obj.yield_strain, obj.yield_strain]  # [stretching, bending]

    def damage_measure(self, m, d, obj, probe, *, peak_strain, peak_force):
        return permanent_dent(m, d, probe)

    def running_damage(self, m, d, obj, probe, *, peak_strain, total_force):
        """Any plastic bending of the card (a crease) counts as damage, stricter than the
        dent, whose spring-back simulation is too slow for every step: twice the limit once any
        plastic strain exists, else 0."""
        a = m.flex_plasticadr[probe.flex]
        crease = float(np.abs(d.plastic[a:]).max()) if d.plastic.size else 0.0
        return obj.damage_limit * 2.0 if crease > 0.0 else 0.0


def permanent_dent(m: mujoco.MjModel, d: mujoco.MjData, probe) -> float:
    """Largest permanent deviation of the box shell from its rest shape [m] (``probe``: the
    trial's object probe, with the flex's vertex slice ``vert`` and ``rest_verts``).

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
