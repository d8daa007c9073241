"""Face press: a finger-sized rigid sphere pushed into the middle of a paper box's side wall.

The mesh check of the box's face (``docs/performance.md``, "Mesh resolution"): a rigid sphere of
:data:`PRESS_RADIUS` on a mocap body moves at :data:`PRESS_SPEED` into the middle of the box's
+x face to ``depth``, holds :data:`PRESS_HOLD_S` and withdraws; a fixed wall behind the far face
keeps the box from sliding. It returns the peak normal force on the sphere and the permanent
dent after spring-back (:func:`gripper.objects.kinds.paper_box.permanent_dent`, the benchmark's own measure).

Example:
    >>> from gripper.experiments.press import face_press
    >>> face_press((5, 5, 6), 0.002)["peak_force_N"]     # doctest: +SKIP
    15.2
"""

from __future__ import annotations

import dataclasses

import mujoco

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.model.builders import build_scene_spec
from gripper.objects.kinds.paper_box import permanent_dent
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement, add_object
from gripper.sim.probes import ObjectProbe, geom_normal_force
from gripper.sim.scene import trial_params

PRESS_RADIUS = 0.007  # m: about a finger pad's curvature across its width
PRESS_SPEED = 0.02  # m/s: a slow, quasi-static press (the 2 mm gap closes in 0.1 s)
PRESS_HOLD_S = 0.3  # s at depth
SETTLE_S = 0.2  # s on the floor before and after


def face_press(points: tuple[int, int, int], depth: float) -> dict:
    """Press the built-in paper box meshed with ``points`` (``GraspObject.mesh_points``) ``depth``
    [m] deep; return ``peak_force_N``, ``dent_m``, ``warnings`` (MuJoCo's) and ``nv``.

    Raises:
        ValueError: ``depth`` outside (0, 10 mm] or a resolution the object refuses.
    """
    if not (isinstance(depth, int | float) and 0.0 < depth <= 0.010):
        raise ValueError(f"press.depth: must be in (0, 0.010] m, got {depth!r}")
    nx, ny, nz = points
    obj = dataclasses.replace(get_object("paper_box"), mesh_points=(nx, ny, nz)).validate()
    p = GripperParams()
    p = trial_params(p)
    spec = build_scene_spec(p, with_object=False)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    add_object(spec, obj, Placement(), rigid_contact=p.contact.model == "pads")
    hx, zc = obj.size[0], obj.size[2] + 0.001
    r = PRESS_RADIUS
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.005, 0.05, 0.05], pos=[-hx - 0.005, 0, zc])
    x0 = hx + r + 0.002
    body = spec.worldbody.add_body(name="probe", mocap=True, pos=[x0, 0, zc])
    body.add_geom(name="probe_geom", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[r, 0, 0], friction=[0.5, 0.005, 1e-4])
    m = spec.compile()
    d = mujoco.MjData(m)
    gid = m.geom("probe_geom").id
    probe = ObjectProbe(m, obj, p.layout.n_fingers, drive_for(p))
    h = m.opt.timestep
    travel = 0.002 + depth
    n_in, n_hold = int(travel / PRESS_SPEED / h), int(PRESS_HOLD_S / h)
    peak = 0.0
    for _ in range(int(SETTLE_S / h)):
        mujoco.mj_step(m, d)
    for i in range(2 * n_in + n_hold):
        s = min(i, n_in) - max(0, i - n_in - n_hold)
        d.mocap_pos[0] = [x0 - travel * s / n_in, 0, zc]
        mujoco.mj_step(m, d)
        peak = max(peak, geom_normal_force(m, d, gid))
    for _ in range(int(SETTLE_S / h)):
        mujoco.mj_step(m, d)
    return {"peak_force_N": peak, "dent_m": permanent_dent(m, d, probe),
            "warnings": int(sum(w.number for w in d.warning)), "nv": int(m.nv)}
