"""A finger pad pressed by a rigid part: the pad's force-indentation as the grasp models realise
it, to check against Hertz's closed form (:func:`gripper.parts.pads.hertz_law`).

One element of the finger (the cable finger's middle element, or the pneumatic finger's full
segment) is fixed with its grasping face up, on its pad exactly as the grippers build it (with
``contact.model = "solver"``: the element's own surface, the solver's contact); a rigid
flat plate of mass ``part_mass`` rests on the face and is pressed down by a force. Gravity is
off, so the force is the contact's whatever the part weighs; the indentation is how far the plate
has moved towards the element since first touch (the pad's slide plus the contact's own
penetration). Steps with the grasp scenes' discrete integrator.

Example:
    >>> from gripper.core.params import GripperParams
    >>> press = press_pad(GripperParams(), [1.0], part_mass=0.05)
    >>> bool(0.3e-3 < press.indentation[0] < 0.6e-3)
    True
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.core.timesteps import TRIAL_TIMESTEP
from gripper.drives import drive_for
from gripper.objects.kinds.rigid import RIGID_CONTACT_SOLIMP, RIGID_CONTACT_SOLREF
from gripper.parts.defaults import add_defaults
from gripper.parts.pads import PadMaker, add_pad_meshes

PLATE_HALF = (0.03, 0.03, 0.002)  # m: a plate wider than any pad
# Each force is held until the plate is at rest: speed below REST_SPEED (1 µm/s, a thousandth of
# the smallest indentation per second), read every SETTLE_CHUNK_S, at most SETTLE_MAX_S (a 1 kg
# plate on the pad's spring rings at a few hertz, damped by the pad's damper).
REST_SPEED = 1e-6  # m/s
SETTLE_CHUNK_S = 0.05  # s
SETTLE_MAX_S = 20.0  # s


@dataclass(frozen=True)
class PadPress:
    """Forces [N] and the steady indentations under them [m]."""

    force: np.ndarray
    indentation: np.ndarray


def _pad_scene(p: GripperParams, part_mass: float, timestep: float) -> mujoco.MjModel:
    spec = mujoco.MjSpec()
    spec.option.timestep = timestep
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    spec.option.gravity = [0.0, 0.0, 0.0]
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    defaults = add_defaults(spec, p)
    drive = drive_for(p)
    add_pad_meshes(spec, drive)
    maker = PadMaker(spec, drive, drive.names(0), defaults)
    seg = spec.worldbody.add_body(name="f0_seg2", pos=[0.0, 0.0, 0.0])
    # a middle element of the finger: its body, its pad's kind and its grasping face's area
    verts, kind, area = drive.element_vertices(2), drive.element_kind(2), drive.face_area(2)
    face = drive.finger_height
    spec.add_mesh(name="element", uservert=verts.ravel().tolist())
    collision = seg.add_geom(defaults["collision"], name="f0_seg2_collision", type=mujoco.mjtGeom.mjGEOM_MESH,
                             meshname="element")
    pads = p.contact.model == "pads"
    if pads:
        maker(seg, 2, kind, collision, verts, area)
    plate = spec.worldbody.add_body(name="part", pos=[0.0, 0.0, face + PLATE_HALF[2]])
    plate.add_joint(name="part_z", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0, 0, 1])  # qvel[0]
    geom = plate.add_geom(name="part_geom", type=mujoco.mjtGeom.mjGEOM_BOX, size=list(PLATE_HALF),
                          mass=part_mass, priority=1, friction=[0.5, 0.005, 1e-4])
    if pads:  # as gripper.objects.scene_objects.add_object builds a rigid part
        geom.solref = list(RIGID_CONTACT_SOLREF)
        geom.solimp = list(RIGID_CONTACT_SOLIMP)
    return spec.compile()


def press_pad(p: GripperParams, forces, *, part_mass: float = 0.05,
              timestep: float = TRIAL_TIMESTEP) -> PadPress:
    """Press the pad of ``p``'s fingers with each force in ``forces`` [N] (in turn, each held to
    rest) through a rigid plate of ``part_mass`` [kg]; return the steady indentations.

    Raises:
        ValueError: a force outside (0, 100] N or a mass outside [1 g, 10 kg].
        RuntimeError: the press went unstable.
    """
    forces = np.asarray(forces, dtype=float)
    if not np.all((forces > 0) & (forces <= 100.0)):
        raise ValueError(f"press_pad.forces: each must be in (0, 100] N, got {forces.tolist()!r}")
    if not 1e-3 <= part_mass <= 10.0:
        raise ValueError(f"press_pad.part_mass: must be in [0.001, 10] kg, got {part_mass!r}")
    m = _pad_scene(p, part_mass, timestep)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    part = m.body("part").id
    z0 = float(d.xpos[part][2])
    chunk = max(1, int(round(SETTLE_CHUNK_S / timestep)))
    out = []
    for f in forces:
        d.xfrc_applied[part, 2] = -f
        for _ in range(int(SETTLE_MAX_S / SETTLE_CHUNK_S)):
            mujoco.mj_step(m, d, chunk)
            if abs(d.qvel[0]) < REST_SPEED:
                break
        else:
            raise RuntimeError(f"press_pad: the plate did not come to rest under {f:g} N in {SETTLE_MAX_S:g} s")
        if not np.isfinite(d.qpos).all() or any(w.number for w in d.warning):
            raise RuntimeError("press_pad: the press went unstable")
        out.append(z0 - float(d.xpos[part][2]))
    return PadPress(force=forces, indentation=np.asarray(out))


__all__ = ["PadPress", "press_pad"]
