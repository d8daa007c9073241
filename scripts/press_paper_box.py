"""Mesh convergence of the paper box's face: a finger-sized sphere pressed into a side wall.

A rigid sphere of 7 mm radius (a finger pad's curvature) on a mocap body moves at 20 mm/s into
the middle of the box's +x face, 2 mm and then 4 mm deep, holds 0.3 s and withdraws; a wall
behind the far face keeps the box from sliding. Printed per mesh resolution (points along x, y,
z): the peak normal force on the sphere [N] and the permanent dent after spring-back [mm]
(:func:`gripper.sim.damage.permanent_dent`, the benchmark's own measure).

Usage: ``.venv/bin/python scripts/press_paper_box.py 4x4x5,5x5x6,6x6x7,8x8x11``
"""
from __future__ import annotations

import dataclasses
import sys

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.core.timesteps import TRIAL_TIMESTEP
from gripper.model.builders import build_scene_spec
from gripper.objects.library import Placement, add_object, get_object
from gripper.sim.damage import permanent_dent
from gripper.sim.probes import ObjectProbe


def press(pts, depth=0.004, r=0.007, speed=0.02, hold=0.3):
    """(peak force [N], dent [m], MuJoCo warnings, nv) of one press at resolution ``pts``."""
    obj = dataclasses.replace(get_object("paper_box"), mesh_points=pts)
    p = GripperParams()
    p = p.replace(sim=p.sim.replace(timestep=TRIAL_TIMESTEP))
    spec = build_scene_spec(p, with_object=False)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    add_object(spec, obj, Placement())
    hx, zc = obj.size[0], obj.size[2] + 0.001
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.005, 0.05, 0.05], pos=[-hx - 0.005, 0, zc])
    x0 = hx + r + 0.002
    body = spec.worldbody.add_body(name="probe", mocap=True, pos=[x0, 0, zc])
    body.add_geom(name="probe_geom", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[r, 0, 0], friction=[0.5, 0.005, 1e-4])
    m = spec.compile()
    d = mujoco.MjData(m)
    gid = m.geom("probe_geom").id
    probe = ObjectProbe(m, obj, p.layout.n_fingers)
    h = m.opt.timestep
    travel = 0.002 + depth
    n_in, n_hold = int(travel / speed / h), int(hold / h)
    peak, f6 = 0.0, np.zeros(6)
    for _ in range(int(0.2 / h)):  # settle on the floor
        mujoco.mj_step(m, d)
    for i in range(2 * n_in + n_hold):
        s = min(i, n_in) - max(0, i - n_in - n_hold)
        d.mocap_pos[0] = [x0 - travel * s / n_in, 0, zc]
        mujoco.mj_step(m, d)
        force = 0.0
        for c in range(d.ncon):
            if gid in (d.contact[c].geom1, d.contact[c].geom2):
                mujoco.mj_contactForce(m, d, c, f6)
                force += abs(f6[0])
        peak = max(peak, force)
    for _ in range(int(0.2 / h)):
        mujoco.mj_step(m, d)
    return peak, permanent_dent(m, d, probe), sum(w.number for w in d.warning), m.nv


def main() -> None:
    for t in (sys.argv[1] if len(sys.argv) > 1 else "4x4x5,5x5x6,6x6x7").split(","):
        pts = tuple(int(v) for v in t.split("x"))
        for depth in (0.002, 0.004):
            f, dent, w, nv = press(pts, depth)
            print(f"{t:8s} depth {1e3 * depth:.0f} mm  peak force {f:6.1f} N  dent {1e3 * dent:6.3f} mm  "
                  f"warnings {w}  nv {nv}", flush=True)


if __name__ == "__main__":
    main()
