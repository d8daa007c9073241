"""Platen crush test: press an object between the floor and a flat rigid plate, release it, and
read its damage measure.

This checks an object's damage model on its own, under a load that does not depend on how the
fingers happen to wrap the object. It shows that the criteria respond when the physics calls for
it: a deep press bursts the balloon (membrane edge strain above its limit) and creases the card
box (a permanent dent after spring-back); a shallow one does neither. The gripper, closed to the
servo's full travel, bursts the balloon and dents the box too (README, "Grasp benchmark").

The plate is a mocap body (it follows its commanded height whatever the reaction): 120 × 120 mm,
10 mm thick, starting ``CRUSH_GAP`` above the object's nominal top. It moves down at ``speed`` to
``depth`` below that top, holds for ``hold_s``, and goes back up at the same speed. The measure
is the one the grasp trials use (:func:`gripper.sim.damage.damage_measure`): peak edge strain for
the balloon and the bag, the permanent dent after :data:`gripper.objects.kinds.paper_box.SPRINGBACK_S` of elastic
spring-back for the paper box, and for rigid parts the peak plate force.

Example:
    >>> from gripper.experiments.crush import crush_test
    >>> res = crush_test("balloon", depth=0.030)          # doctest: +SKIP
    >>> res["damaged"], round(res["damage_measure"], 2)   # doctest: +SKIP
"""

from __future__ import annotations

import math

import mujoco

from gripper.core.params import GripperParams
from gripper.core.timesteps import TRIAL_TIMESTEP
from gripper.drives import drive_for
from gripper.experiments.protocol import CRUSH_HOLD_S, CRUSH_SPEED
from gripper.model.builders import build_scene_spec
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement, add_object
from gripper.sim.canonical import apply_canonical_constants
from gripper.sim.damage import damage_measure
from gripper.sim.probes import ObjectProbe, geom_normal_force
from gripper.sim.scene import trial_params
from gripper.sim.stability import check_stable

# Gap between the plate and the object's top at the start [m]: clears the 1 mm drop gap.
CRUSH_GAP = 0.005
# Time for the object to settle on the floor before the plate moves [s] (as GraspProtocol).
CRUSH_SETTLE_S = 0.3
PLATE_HALF = (0.060, 0.060, 0.005)  # m: wider than every library object


def crush_test(obj: str | GraspObject, depth: float, *, speed: float = CRUSH_SPEED,
               hold_s: float = CRUSH_HOLD_S, params: GripperParams | None = None) -> dict:
    """Press ``obj`` to ``depth`` [m] below its top at ``speed`` [m/s], hold ``hold_s`` [s], release.

    Returns:
        dict with ``object``, ``depth_m``, ``damage_measure`` (the object's own measure, see the
        module docstring), ``damage_limit``, ``damaged``, ``peak_plate_force_N`` and
        ``damage_measure_name``.

    Raises:
        ValueError: unknown object, or depth / speed / hold_s out of range.
        SimulationUnstable: MuJoCo warned or the state became non-finite.
    """
    obj = get_object(obj) if isinstance(obj, str) else obj.validate()
    height = 2.0 * obj.size[2]
    if not (isinstance(depth, int | float) and math.isfinite(depth) and 0.0 < depth < height):
        raise ValueError(f"crush.depth: must be in (0, {height:g}) m (the object's height), got {depth!r}")
    if not (isinstance(speed, int | float) and math.isfinite(speed) and 1e-3 <= speed <= 1.0):
        raise ValueError(f"crush.speed: must be in [0.001, 1] m/s, got {speed!r}")
    if not (isinstance(hold_s, int | float) and math.isfinite(hold_s) and 0.0 <= hold_s <= 10.0):
        raise ValueError(f"crush.hold_s: must be in [0, 10] s, got {hold_s!r}")
    p = (params or GripperParams()).validate()
    p = trial_params(p).validate()
    spec = build_scene_spec(p, with_object=False)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    add_object(spec, obj, Placement(), rigid_contact=p.contact.model == "pads")
    z_top = height + CRUSH_GAP + PLATE_HALF[2]  # plate centre at the start
    plate = spec.worldbody.add_body(name="platen", mocap=True, pos=[0.0, 0.0, z_top])
    plate.add_geom(name="platen_geom", type=mujoco.mjtGeom.mjGEOM_BOX, size=list(PLATE_HALF),
                   friction=[0.5, 0.005, 1e-4], rgba=[0.6, 0.6, 0.6, 0.5])
    m = spec.compile()
    apply_canonical_constants(m, obj, Placement())
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    probe = ObjectProbe(m, obj, p.layout.n_fingers, drive_for(p))
    plate_geom = m.geom("platen_geom").id
    travel = CRUSH_GAP + depth
    t_move = travel / speed
    schedule = [(CRUSH_SETTLE_S, lambda t: 0.0), (t_move, lambda t: -speed * t),
                (hold_s, lambda t: -travel), (t_move, lambda t: -travel + speed * t)]
    peak_strain = peak_force = 0.0
    for duration, offset in schedule:
        t0 = d.time
        for _ in range(int(round(duration / TRIAL_TIMESTEP))):
            d.mocap_pos[0, 2] = z_top + offset(d.time - t0)
            mujoco.mj_step(m, d)
            peak_force = max(peak_force, geom_normal_force(m, d, plate_geom))
            peak_strain = max(peak_strain, probe.edge_strain(d))
        check_stable(m, d, f"crush test of {obj.name}")
    measure = damage_measure(m, d, obj, probe, peak_strain=peak_strain, peak_force=peak_force)
    return {"object": obj.name, "depth_m": float(depth), "damage_measure": float(measure),
            "damage_measure_name": obj.damage_measure, "damage_limit": obj.damage_limit,
            "damaged": obj.is_damaged(measure), "peak_plate_force_N": float(peak_force)}


__all__ = ["crush_test"]
