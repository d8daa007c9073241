"""The cable finger in the MJCF: paper 000's element chain on its bridges, the cable through the
holes, the reel and the servo that pulls it (structure: ``gripper.model.builders``'s docstring),
and the single finger of the bending test.

Example:
    >>> from gripper.core.params import GripperParams
    >>> from gripper.drives.cable.finger import build_bending_spec
    >>> build_bending_spec(GripperParams()).compile().nu    # the servo
    1
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.core.params import DEG, GripperParams
from gripper.drives.cable.closure import teeth_lock_angle, tune_closure_limits
from gripper.drives.cable.geometry import (
    cable_line_z,
    cable_via_points,
    element_face,
    element_kind,
    element_vertices,
)
from gripper.drives.cable.servo import add_servo, set_dcmotor
from gripper.parts.defaults import PAD_HALF_THICKNESS, add_defaults, set_options, set_rigid_stop
from gripper.parts.names import MODEL_NAME, FingerNames

# Cable-reel body: a light drum carriage. Its inertia barely matters: the servo's reflected
# rotor inertia (actuator armature / spool radius², ≈ 3.8 kg for the hobby preset) dominates.
REEL_MASS = 1.0e-3  # kg


# Distance from the palm face back to the cable guide and on to the reel, along the finger
# axis inside the palm [m]: keeps via points apart so the tendon path is well defined.
GUIDE_DEPTH = 0.004


REEL_DEPTH = 0.010


# Lower end of each hinge joint's own range [rad]: out of reach, the extension stop is a tendon
# (and the upper end of that tendon's range where no lock applies).
EXTENSION_JOINT_RANGE = math.pi / 2


# Cable (tendon) limit constraint: impedance at the limit. 0.99 keeps the rope's stretch small.
CABLE_SOLIMP = (0.99, 0.99, 0.001, 0.5, 2.0)



def add_hinge_defaults(spec: mujoco.MjSpec, defaults: dict, p: GripperParams) -> None:
    """One class per hinge index, ``hinge{j}`` under ``hinge``: what hinge j has on every finger
    (its position on the bridge, range, spring, damper and rest angle), stated once."""
    g = p.finger
    stiff, damp, rest = p.springs.per_hinge(g.n_hinges)
    for j in range(2, g.n_segments + 1):
        cls = spec.add_default(f"hinge{j}", defaults["hinge"])
        cls.joint.pos = [0, 0, g.hinge_z]
        cls.joint.range = [-EXTENSION_JOINT_RANGE, g.closure_angle_deg * DEG]
        cls.joint.stiffness = [stiff[j - 2], 0, 0]
        cls.joint.damping = [damp[j - 2], 0, 0]
        cls.joint.springref = rest[j - 2] * DEG
        defaults[f"hinge{j}"] = cls


def add_servo_default(spec: mujoco.MjSpec, root: mujoco.MjsDefault, p: GripperParams) -> mujoco.MjsDefault:
    """The ``servo`` class: every finger's dcmotor shares its datasheet and position loop
    (:mod:`gripper.drives.cable.servo`)."""
    servo = spec.add_default("servo", root)
    set_dcmotor(servo.actuator, p)
    return servo


def add_element_meshes(spec: mujoco.MjSpec, p: GripperParams) -> None:
    kinds = {element_kind(i, p.finger.n_segments) for i in range(p.finger.n_segments)}
    for kind in sorted(kinds):
        spec.add_mesh(name=f"element_{kind}",
                      uservert=element_vertices(p.finger, kind).ravel().tolist())


def add_finger(spec: mujoco.MjSpec, parent: mujoco.MjsBody, p: GripperParams, prefix: str,
               pos, quat, defaults: dict, pad=None) -> FingerNames:
    """Add one finger (mount frame, element chain, pads, cable sites, reel) under ``parent``.

    ``pos``/``quat`` place the finger frame in ``parent``'s frame. ``pad``: a
    :class:`gripper.parts.pads.PadMaker` that puts each element's surface on a compliant pad
    (None: the element's own geom collides). Returns the names.
    """
    g = p.finger
    names = FingerNames(prefix, g.n_segments)
    stiff, damp, rest = p.springs.per_hinge(g.n_hinges)
    zc = cable_line_z(g, p.cable)
    mount = parent.add_body(name=names.mount, pos=list(pos), quat=list(quat))
    mount.add_site(name=names.cable_guide, pos=[-GUIDE_DEPTH, 0, zc], size=[0.001] * 3)
    reel = mount.add_body(name=names.reel, pos=[-REEL_DEPTH, 0, zc])
    reel.add_geom(defaults["visual"], name=f"{prefix}_reel_drum", type=mujoco.mjtGeom.mjGEOM_SPHERE,
                  size=[0.003, 0, 0], mass=REEL_MASS, material="cable")
    reel.add_joint(name=names.reel, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[-1, 0, 0],
                   limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                   range=[-0.002, p.servo.datasheet.travel * p.servo.spool_radius + 0.002])
    reel.add_site(name=names.reel_site, size=[0.001] * 3)

    # Upper end of each hinge's rigid stop tendon: the squashed teeth's lock, or out of reach.
    lock = (g.closure_angle_deg * DEG + teeth_lock_angle(g) if p.springs.closure == "teeth"
            else EXTENSION_JOINT_RANGE)
    body = mount
    for i in range(g.n_segments):
        kind = element_kind(i, g.n_segments)
        j = i + 1
        seg = body.add_body(name=names.body(j), pos=[g.pitch if i else 0.0, 0, 0])
        if i > 0:
            # Neighbours share the bridge; their contact is the joint limit (cut closing), so
            # their convex hulls must not collide (MuJoCo's parent filter skips world-welded
            # parents, so exclude explicitly).
            spec.add_exclude(bodyname1=body.name, bodyname2=seg.name)
            # The joint's own limit is the closed cut (its upper end; the lower end is out of
            # reach). The rigid stops are a one-joint fixed tendon with its own limit: extension
            # at its lower end, the squashed teeth's lock at its upper end (gripper.drives.cable.closure).
            # MuJoCo gives a joint limit one solref/solimp for both ends, and the cut's
            # compliant stop must not soften the extension stop.
            hinge_name = names.hinge(j)
            seg.add_joint(defaults.get(f"hinge{j}", defaults["hinge"]), name=hinge_name, pos=[0, 0, g.hinge_z],
                          range=[-EXTENSION_JOINT_RANGE, g.closure_angle_deg * DEG],
                          stiffness=[stiff[i - 1], 0, 0], damping=[damp[i - 1], 0, 0],
                          springref=rest[i - 1] * DEG)
            stop = spec.add_tendon(name=f"{hinge_name}_stops", limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                                   range=[-g.extension_limit_deg * DEG, lock])
            stop.wrap_joint(hinge_name, 1.0)
            set_rigid_stop(stop, p)
        seg.add_geom(defaults["visual"], name=names.visual(j),
                     type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"element_{kind}", material="silicone")
        collision = seg.add_geom(defaults["collision"], name=names.collision(j),
                                 type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"element_{kind}")
        x0, x1, face_width = element_face(g, kind)
        host = seg if pad is None else pad(seg, j, kind, collision, element_vertices(g, kind),
                                           (x1 - x0) * face_width)
        host.add_site(defaults["pad"], name=names.pad(j),
                     pos=[0.5 * (x0 + x1), 0, g.height],
                     size=[0.5 * (x1 - x0), 0.5 * face_width, PAD_HALF_THICKNESS])
        for role, x in cable_via_points(g, p.cable, kind):
            name = names.tip_anchor if role == "anchor" else names.cable_site(j)
            seg.add_site(name=name, pos=[x, 0, zc], size=[0.0008] * 3)
        if kind == "tip":
            seg.add_site(name=names.tip, pos=[g.pitch, 0, g.hinge_z], size=[0.001] * 3)
        body = seg
    return names


def straight_cable_length(p: GripperParams) -> float:
    """Tendon length with the finger straight and the reel at zero [m] (collinear path)."""
    return REEL_DEPTH + p.finger.length


def add_cable_drive(spec: mujoco.MjSpec, p: GripperParams, names: FingerNames,
                    servo_class: mujoco.MjsDefault | None = None) -> None:
    """The cable tendon of one finger and the servo that reels it in, plus their sensors."""
    g = p.finger
    ten = spec.add_tendon(name=names.cable, width=0.5 * p.cable.diameter,
                          material="cable", frictionloss=p.cable.friction_loss,
                          limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                          range=[0.0, straight_cable_length(p)])
    ten.solimp_limit = list(CABLE_SOLIMP)
    ten.wrap_site(names.reel_site)
    ten.wrap_site(names.cable_guide)
    for j in range(1, g.n_segments + 1):
        kind = element_kind(j - 1, g.n_segments)
        for role, _ in cable_via_points(g, p.cable, kind):
            ten.wrap_site(names.tip_anchor if role == "anchor" else names.cable_site(j))

    add_servo(spec, p, names.servo, names.reel, servo_class)

    S = mujoco.mjtSensor
    for h in names.hinges:
        spec.add_sensor(name=f"{h}_angle", type=S.mjSENS_JOINTPOS, objname=h,
                        objtype=mujoco.mjtObj.mjOBJ_JOINT)
    spec.add_sensor(name=f"{names.cable}_length", type=S.mjSENS_TENDONPOS, objname=names.cable,
                    objtype=mujoco.mjtObj.mjOBJ_TENDON)
    spec.add_sensor(name=f"{names.cable}_tension", type=S.mjSENS_TENDONLIMITFRC,
                    objname=names.cable, objtype=mujoco.mjtObj.mjOBJ_TENDON)
    spec.add_sensor(name=f"{names.servo}_angle", type=S.mjSENS_ACTUATORPOS,
                    objname=names.servo, objtype=mujoco.mjtObj.mjOBJ_ACTUATOR)
    spec.add_sensor(name=f"{names.servo}_torque", type=S.mjSENS_ACTUATORFRC,
                    objname=names.servo, objtype=mujoco.mjtObj.mjOBJ_ACTUATOR)
    for pad in names.pads:
        spec.add_sensor(name=pad, type=S.mjSENS_TOUCH, objname=pad,
                        objtype=mujoco.mjtObj.mjOBJ_SITE)


def tune_soft_limits(spec: mujoco.MjSpec, p: GripperParams) -> None:
    """Set the cable limits' and the hinge limits' ``solref`` from physical stiffnesses (the
    cable's EA/L, the closed cut's): compiles once to read the inverse inertias."""
    model = spec.compile()
    tune_cable_stiffness(spec, p, model)
    tune_closure_limits(spec, p, model)


def tune_cable_stiffness(spec: mujoco.MjSpec, p: GripperParams, model: mujoco.MjModel) -> None:
    """Set each cable limit's ``solref`` so the rope stretches like a cable of stiffness EA/L.

    A MuJoCo limit with time constant tau, damping ratio 1 and impedance d behaves, for a slow
    load, like a spring of stiffness k = 1 / (tau² (1-d) A), A being the tendon's inverse inertia
    (``tendon_invweight0``). Solving for tau gives the cable's EA/L; tau is kept >= 2 time steps,
    MuJoCo's stability floor (then the rope is softer than the real cable: documented in the
    model README). ``model`` is ``spec`` compiled; edits ``spec`` in place.
    """
    d = CABLE_SOLIMP[1]
    for t in spec.tendons:
        if not t.name.endswith("_cable"):
            continue
        tid = model.tendon(t.name).id
        k = p.cable.axial_stiffness / straight_cable_length(p)
        inv_w = float(model.tendon_invweight0[tid])
        tau = 1.0 / math.sqrt(k * (1.0 - d) * inv_w)
        t.solref_limit = [round(max(tau, 2.0 * p.sim.timestep), 6), 1.0]


def build_bending_spec(p: GripperParams, *, timestep: float | None = None) -> mujoco.MjSpec:
    """One finger clamped at B1 to the world, with its reel and servo: the paper's bending test.

    The finger lies horizontal along world +x and bends in the horizontal plane (grasping face
    towards +y, hinge axes vertical), so gravity loads the hinges' bearings, not their springs:
    the test measures the cable-spring balance alone, as in paper 000 §IV.
    """
    p.validate()
    if timestep is not None:
        p = p.replace(sim=p.sim.replace(timestep=timestep))
    spec = mujoco.MjSpec()
    set_options(spec, p)
    spec.modelname = f"{MODEL_NAME}_bending"
    defaults = add_defaults(spec, p)
    defaults["servo"] = add_servo_default(spec, defaults["root"], p)
    add_element_meshes(spec, p)
    quat = np.zeros(4)
    rot = np.column_stack([[1, 0, 0], [0, 0, -1], [0, 1, 0]]).astype(float)
    mujoco.mju_mat2Quat(quat, rot.ravel())
    names = add_finger(spec, spec.worldbody, p, "f0", [0, 0, 0.1], quat, defaults)
    add_cable_drive(spec, p, names, defaults["servo"])
    spec.worldbody.add_camera(name="top", pos=[0.05, 0.03, 0.35], xyaxes=[1, 0, 0, 0, 1, 0])
    tune_soft_limits(spec, p)
    return spec
