"""Build the gripper (and its scenes) as a ``mujoco.MjSpec`` from :class:`GripperParams`.

Structure of the generated model (names use ``f{k}_`` for finger k, elements 1-based as in
paper 000, B1 = ``seg1`` fixed to the palm; hinge ``hinge{j}`` joins ``seg{j-1}`` and ``seg{j}``
and carries spring M_j):

- ``palm`` on slide joints ``lift_x``, ``lift_y`` (optional) and ``lift_z``, each driven by a
  position actuator of the same name;
- per finger, a ``mount`` frame (finger frame, see :mod:`gripper.model.geometry`), the element chain,
  a ``reel`` body on a slide joint: the cable pulled onto the spool;
- per finger, a spatial tendon ``f{k}_cable`` from the reel through a site at each hole mouth to
  the tip anchor, limited to its straight-finger length: a rope (the limit is one-sided: it can
  go slack and never pushes);
- per finger, a ``dcmotor`` ``f{k}_servo`` on the reel joint with gear 1/spool radius, so the
  actuator length is the spool angle [rad] and its force the shaft torque [N·m];
- sensors: hinge angles, cable length and tension, servo angle and torque, pad touch forces.

Example:
    >>> import mujoco
    >>> from gripper import GripperParams, build_gripper_spec
    >>> model = build_gripper_spec(GripperParams()).compile()
    >>> model.nu    # 4 servos + 3 lift axes
    7
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.core.params import DEG, GripperParams
from gripper.model.closure import MIN_STEPS, RIGID_STOP_SOLIMP, teeth_lock_angle, tune_closure_limits
from gripper.model.geometry import (
    cable_line_z,
    cable_via_points,
    element_kind,
    element_profile,
    element_vertices,
)
from gripper.model.names import MODEL_NAME, FingerNames, finger_name
from gripper.model.pads import PadMaker, add_pad_meshes
from gripper.objects.library import get_object
from gripper.pneumatic.chamber import add_pneumatic_finger, add_segment_meshes
from gripper.servo.actuator import add_servo, set_dcmotor

SILICONE_RGBA = (0.93, 0.93, 0.88, 1.0)


PALM_RGBA = (0.25, 0.27, 0.30, 1.0)


CABLE_RGBA = (0.85, 0.35, 0.10, 1.0)


# Cable-reel body: a light drum carriage. Its inertia barely matters: the servo's reflected
# rotor inertia (actuator armature / spool radius², ≈ 3.8 kg for the hobby preset) dominates.
REEL_MASS = 1.0e-3  # kg


# Distance from the palm face back to the cable guide and on to the reel, along the finger
# axis inside the palm [m]: keeps via points apart so the tendon path is well defined.
GUIDE_DEPTH = 0.004


REEL_DEPTH = 0.010


# Touch-pad sites: thickness of the sensing slab on each grasping face [m]; it must hold the
# contact points of a few millimetres of penetration.
PAD_HALF_THICKNESS = 0.0025


# Lower end of each hinge joint's own range [rad]: out of reach, the extension stop is a tendon
# (and the upper end of that tendon's range where no lock applies).
EXTENSION_JOINT_RANGE = math.pi / 2


# Cable (tendon) limit constraint: impedance at the limit. 0.99 keeps the rope's stretch small.
CABLE_SOLIMP = (0.99, 0.99, 0.001, 0.5, 2.0)


def add_defaults(spec: mujoco.MjSpec, p: GripperParams) -> dict[str, mujoco.MjsDefault]:
    """Menagerie-style default classes (root, visual, collision, hinge, pad, servo) and the named
    materials the visual geoms and cables use."""
    root = spec.add_default(MODEL_NAME, spec.default)
    visual = spec.add_default("visual", root)
    visual.geom.contype = 0
    visual.geom.conaffinity = 0
    visual.geom.group = 2
    visual.geom.density = 0.0
    collision = spec.add_default("collision", root)
    collision.geom.group = 3
    collision.geom.friction = [p.material.friction, 0.005, 1e-4]
    collision.geom.density = p.material.density
    collision.geom.rgba = [0.5, 0.6, 0.9, 0.4]
    hinge = spec.add_default("hinge", root)
    hinge.joint.type = mujoco.mjtJoint.mjJNT_HINGE
    hinge.joint.axis = [0, -1, 0]  # positive angle closes the cut (curls towards +z)
    hinge.joint.limited = mujoco.mjtLimited.mjLIMITED_TRUE
    # Closed cut = silicone face on silicone face, far stiffer than the bridge: a stiff limit
    # (time constant four steps, impedance 0.9995). A limit's static overrun grows as
    # (1 - d) x timeconst^2 / (effective inertia), and the distal segments weigh grams, so d sets
    # it: 0.999 let a hinge overrun 0.64° at stall tension at 5e-4 s (12° at the trials' 2 ms);
    # 0.9995 gives 0.32° (6° at 2 ms). 0.9998 and 0.9999 (MuJoCo's cap) diverged in random-control
    # smoke runs of 12-element fingers at 1 ms, as did a two-step time constant.
    # This is the rigid stop (springs.closure = "rigid"); the default compliant closure sets each
    # hinge's time constant from the teeth's stiffness instead (gripper.model.closure).
    _set_rigid_stop(hinge.joint, p)
    pad = spec.add_default("pad", root)
    pad.site.type = mujoco.mjtGeom.mjGEOM_BOX
    pad.site.group = 4
    pad.site.rgba = [0.1, 0.8, 0.1, 0.3]
    # The servo: every finger's dcmotor shares its datasheet and position loop (gripper.servo.actuator)
    servo = spec.add_default("servo", root)
    set_dcmotor(servo.actuator, p)
    add_materials(spec)
    return {"root": root, "visual": visual, "collision": collision, "hinge": hinge, "pad": pad, "servo": servo}


# Named materials of the visual geoms and the cables (Menagerie's grippers name theirs too).
MATERIALS = {"silicone": SILICONE_RGBA, "palm": PALM_RGBA, "cable": CABLE_RGBA}


def add_materials(spec: mujoco.MjSpec) -> None:
    for name, rgba in MATERIALS.items():
        spec.add_material(name=name, rgba=list(rgba))


def _set_rigid_stop(owner, p: GripperParams) -> None:
    """A limit as stiff as the step allows (``MIN_STEPS`` steps, impedance 0.9995) on a joint
    default or a tendon."""
    owner.solref_limit = [MIN_STEPS * p.sim.timestep, 1.0]
    owner.solimp_limit = list(RIGID_STOP_SOLIMP)


def add_element_meshes(spec: mujoco.MjSpec, p: GripperParams) -> None:
    kinds = {element_kind(i, p.finger.n_segments) for i in range(p.finger.n_segments)}
    for kind in sorted(kinds):
        spec.add_mesh(name=f"element_{kind}",
                      uservert=element_vertices(p.finger, kind).ravel().tolist())


def add_finger(spec: mujoco.MjSpec, parent: mujoco.MjsBody, p: GripperParams, prefix: str,
               pos, quat, defaults: dict, pad=None) -> FingerNames:
    """Add one finger (mount frame, element chain, pads, cable sites, reel) under ``parent``.

    ``pos``/``quat`` place the finger frame in ``parent``'s frame. ``pad``: a
    :class:`gripper.model.pads.PadMaker` that puts each element's surface on a compliant pad
    (None: the element's own geom collides). Returns the names.
    """
    g = p.finger
    names = FingerNames(prefix, g.n_segments)
    stiff, damp, rest = p.springs.per_hinge(g.n_hinges)
    zc = cable_line_z(g, p.cable)
    mount = parent.add_body(name=names.mount, pos=list(pos), quat=list(quat))
    mount.add_site(name=f"{prefix}_cable_guide", pos=[-GUIDE_DEPTH, 0, zc], size=[0.001] * 3)
    reel = mount.add_body(name=names.reel, pos=[-REEL_DEPTH, 0, zc])
    reel.add_geom(defaults["visual"], name=f"{prefix}_reel_drum", type=mujoco.mjtGeom.mjGEOM_SPHERE,
                  size=[0.003, 0, 0], mass=REEL_MASS, material="cable")
    reel.add_joint(name=names.reel, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[-1, 0, 0],
                   limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                   range=[-0.002, p.servo.datasheet.travel * p.servo.spool_radius + 0.002])
    reel.add_site(name=f"{prefix}_reel_site", size=[0.001] * 3)

    # Upper end of each hinge's rigid stop tendon: the squashed teeth's lock, or out of reach.
    lock = (g.closure_angle_deg * DEG + teeth_lock_angle(g) if p.springs.closure == "teeth"
            else EXTENSION_JOINT_RANGE)
    body = mount
    for i in range(g.n_segments):
        kind = element_kind(i, g.n_segments)
        j = i + 1
        seg = body.add_body(name=f"{prefix}_seg{j}", pos=[g.pitch if i else 0.0, 0, 0])
        if i > 0:
            # Neighbours share the bridge; their contact is the joint limit (cut closing), so
            # their convex hulls must not collide (MuJoCo's parent filter skips world-welded
            # parents, so exclude explicitly).
            spec.add_exclude(bodyname1=body.name, bodyname2=seg.name)
            # The joint's own limit is the closed cut (its upper end; the lower end is out of
            # reach). The rigid stops are a one-joint fixed tendon with its own limit: extension
            # at its lower end, the squashed teeth's lock at its upper end (gripper.model.closure).
            # MuJoCo gives a joint limit one solref/solimp for both ends, and the cut's
            # compliant stop must not soften the extension stop.
            hinge_name = f"{prefix}_hinge{j}"
            seg.add_joint(defaults["hinge"], name=hinge_name, pos=[0, 0, g.hinge_z],
                          range=[-EXTENSION_JOINT_RANGE, g.closure_angle_deg * DEG],
                          stiffness=[stiff[i - 1], 0, 0], damping=[damp[i - 1], 0, 0],
                          springref=rest[i - 1] * DEG)
            stop = spec.add_tendon(name=f"{hinge_name}_stops", limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                                   range=[-g.extension_limit_deg * DEG, lock])
            stop.wrap_joint(hinge_name, 1.0)
            _set_rigid_stop(stop, p)
        seg.add_geom(defaults["visual"], name=f"{prefix}_seg{j}_visual",
                     type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"element_{kind}", material="silicone")
        collision = seg.add_geom(defaults["collision"], name=f"{prefix}_seg{j}_collision",
                                 type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"element_{kind}")
        prof = element_profile(g, kind)
        top = prof[np.isclose(prof[:, 1], g.height), 0]
        x0, x1 = float(top.min()), float(top.max())
        host = seg if pad is None else pad(seg, j, kind, collision, element_vertices(g, kind),
                                           (x1 - x0) * g.width)
        host.add_site(defaults["pad"], name=f"{prefix}_seg{j}_pad",
                     pos=[0.5 * (x0 + x1), 0, g.height],
                     size=[0.5 * (x1 - x0), 0.5 * g.width, PAD_HALF_THICKNESS])
        for role, x in cable_via_points(g, p.cable, kind):
            name = f"{prefix}_tip_anchor" if role == "anchor" else f"{prefix}_seg{j}_cable"
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
    ten.wrap_site(f"{names.prefix}_reel_site")
    ten.wrap_site(f"{names.prefix}_cable_guide")
    for j in range(1, g.n_segments + 1):
        kind = element_kind(j - 1, g.n_segments)
        for role, _ in cable_via_points(g, p.cable, kind):
            ten.wrap_site(f"{names.prefix}_tip_anchor" if role == "anchor"
                          else f"{names.prefix}_seg{j}_cable")

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
    cable's EA/L, the closed cut's): compiles once to read the inverse inertias. The pneumatic
    finger has neither (its hinges' range is far past its calibrated bend)."""
    if p.pneumatic_fingers:
        return
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


def set_options(spec: mujoco.MjSpec, p: GripperParams) -> None:
    spec.modelname = MODEL_NAME
    spec.compiler.degree = False
    spec.compiler.autolimits = True
    spec.option.timestep = p.sim.timestep
    spec.option.integrator = {
        "euler": mujoco.mjtIntegrator.mjINT_EULER,
        "implicit": mujoco.mjtIntegrator.mjINT_IMPLICIT,
        "implicitfast": mujoco.mjtIntegrator.mjINT_IMPLICITFAST,
        "rk4": mujoco.mjtIntegrator.mjINT_RK4,
    }[p.sim.integrator]
    if p.pneumatic_fingers:
        # The pneumatic chain's short end segments on stiff hinges ring at some 300 Hz: springs
        # integrated explicitly (implicitfast, implicit, rk4) diverged at 1 ms under the random-
        # command check (at 35-76 ms); MuJoCo's discrete integrator, implicit in the springs (the
        # trials' integrator), is stable there and at the trials' 2 ms.
        spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    spec.option.gravity = [0, 0, -p.sim.gravity]
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.impratio = 10  # stiff friction, as Menagerie grippers use, against object slip
    # Solver bookkeeping only (the same constrained problem is solved; results agree to the
    # solver tolerance). Sparse constraint Jacobian: MuJoCo's "auto" picks dense below 60 dofs,
    # but every contact here touches only the object's 6 dofs, one finger's chain and the stage,
    # and the elliptic-cone Hessian updates cost less sparse: mj_step 19 % faster under random
    # environment actions and 3-13 % in grasp trials (nv 33, medians of 3). No constraint
    # islands: a grasp joins palm, fingers and object into one island, so splitting is pure
    # overhead (5-12 % on rigid-object grasps, ±5 % on flex objects, within noise).
    spec.option.jacobian = mujoco.mjtJacobian.mjJAC_SPARSE
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_ISLAND


def finger_height(p: GripperParams) -> float:
    """Height of the gripper's fingers from back to grasping face [m], whichever they are."""
    return p.pneumatic.height if p.pneumatic_fingers else p.finger.height


def add_fingers(spec: mujoco.MjSpec, parent: mujoco.MjsBody, p: GripperParams, defaults: dict) -> list[FingerNames]:
    """Every finger on the palm (cable or pneumatic, ``p.actuation``) with its drive."""
    out = []
    pads = p.contact.model == "pads"
    if pads:
        add_pad_meshes(spec, p)
    for k in range(p.layout.n_fingers):
        pos, quat = finger_mount_pose(p, k)
        if p.pneumatic_fingers:
            names = FingerNames(finger_name(k), p.pneumatic.n_segments, pneumatic=True)
            maker = PadMaker(spec, p, names, defaults) if pads else None
            add_pneumatic_finger(spec, parent, p, names, pos, quat, defaults, maker)
        else:
            names = FingerNames(finger_name(k), p.finger.n_segments)
            maker = PadMaker(spec, p, names, defaults) if pads else None
            add_finger(spec, parent, p, finger_name(k), pos, quat, defaults, maker)
            add_cable_drive(spec, p, names, defaults["servo"])
        if maker is not None:
            maker.exclude_neighbours()
        out.append(names)
    return out


def finger_mount_pose(p: GripperParams, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Position and quaternion of finger ``k``'s frame in the palm frame.

    The palm frame has z up and its face at z = 0; finger x points down, the grasping face
    (finger z) looks at the palm axis, fingers evenly spaced by azimuth 2πk/n.
    """
    phi = 2.0 * math.pi * k / p.layout.n_fingers
    c, s = math.cos(phi), math.sin(phi)
    radial = p.layout.palm_radius + finger_height(p)
    pos = np.array([radial * c, radial * s, 0.0])
    rot = np.column_stack([[0, 0, -1], [s, -c, 0], [-c, -s, 0]]).astype(float)
    tilt = p.layout.mount_tilt_deg * DEG
    ry = np.array([[math.cos(tilt), 0, math.sin(tilt)], [0, 1, 0],
                   [-math.sin(tilt), 0, math.cos(tilt)]])
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, (rot @ ry).ravel())
    return pos, quat


def build_gripper_spec(p: GripperParams) -> mujoco.MjSpec:
    """The gripper on its lift stage, no floor or object (see :func:`build_scene_spec`).

    Raises:
        ValueError: invalid parameters.
    """
    p.validate()
    spec = mujoco.MjSpec()
    set_options(spec, p)
    defaults = add_defaults(spec, p)
    if p.pneumatic_fingers:
        add_segment_meshes(spec, p)
    else:
        add_element_meshes(spec, p)

    lift = p.lift
    palm = spec.worldbody.add_body(name="palm", pos=[0, 0, lift.home_height], childclass=MODEL_NAME)
    # The stage's own controller holds the palm's weight (integral action of a real linear
    # stage); the fingers keep their weight and sag under it.
    palm.gravcomp = 1.0
    axes = [("lift_x", [1, 0, 0]), ("lift_y", [0, 1, 0])] if lift.xy_enabled else []
    axes.append(("lift_z", [0, 0, 1]))
    for name, axis in axes:
        travel = lift.z_travel if name == "lift_z" else lift.xy_travel
        palm.add_joint(name=name, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=axis,
                       range=[-travel, travel], limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                       armature=0.0, damping=0.0)
    radius = p.layout.palm_radius + finger_height(p) + 0.004
    palm.add_geom(defaults["visual"], name="palm_visual", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                  size=[radius, 0.5 * p.layout.palm_thickness, 0],
                  pos=[0, 0, 0.5 * p.layout.palm_thickness], material="palm")
    palm.add_geom(defaults["collision"], name="palm_collision",
                  type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                  size=[radius, 0.5 * p.layout.palm_thickness, 0],
                  pos=[0, 0, 0.5 * p.layout.palm_thickness], mass=p.layout.palm_mass)
    palm.add_site(name="palm_center", pos=[0, 0, 0], size=[0.002] * 3)
    palm.add_camera(name="palm_cam", pos=[0, 0, -0.005], quat=[0, 1, 0, 0], fovy=90)

    add_fingers(spec, palm, p, defaults)

    for name, _ in axes:
        act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=lift.stiffness,
                            kv=2.0 * lift.damping_ratio * math.sqrt(lift.stiffness * p.layout.palm_mass))
        travel = lift.z_travel if name == "lift_z" else lift.xy_travel
        act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
        act.ctrlrange = [-travel, travel]
        act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
        act.forcerange = [-lift.max_force, lift.max_force]
        spec.add_sensor(name=f"{name}_pos", type=mujoco.mjtSensor.mjSENS_JOINTPOS,
                        objname=name, objtype=mujoco.mjtObj.mjOBJ_JOINT)
    spec.add_sensor(name="palm_pos", type=mujoco.mjtSensor.mjSENS_FRAMEPOS, objname="palm_center",
                    objtype=mujoco.mjtObj.mjOBJ_SITE)
    tune_soft_limits(spec, p)
    if p.contact.model == "pads":
        # The pads' stiff springs on light bodies need MuJoCo's discrete integrator, implicit in
        # the springs (gripper.model.pads), as the grasp scenes take anyway; set after the limits
        # are tuned, whose match to that integrator the grasp scenes make once per design
        # (gripper.sim.scene).
        spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    return spec


def build_scene_spec(p: GripperParams, *, with_object: bool = True) -> mujoco.MjSpec:
    """Gripper plus floor, lights, cameras and (optionally) a rigid test block under the palm.

    The test block is the object library's ``block`` (its size, mass and friction).
    """
    spec = build_gripper_spec(p)
    add_scene_dressing(spec)
    if with_object:
        block = get_object("block")
        obj = spec.worldbody.add_body(name="object", pos=[0, 0, block.size[2]])
        obj.add_freejoint(name="object_free")
        obj.add_geom(name="object_geom", type=mujoco.mjtGeom.mjGEOM_BOX,
                     size=list(block.size), mass=block.mass, friction=[block.friction, 0.005, 1e-4],
                     rgba=[0.2, 0.5, 0.8, 1])
    return spec


def add_scene_dressing(spec: mujoco.MjSpec) -> None:
    """Floor, light, the ``front`` and ``side`` cameras and the offscreen buffer: what the scene
    adds to the gripper (the committed ``scene.xml`` holds exactly this beside its include)."""
    spec.visual.global_.offwidth = 640
    spec.visual.global_.offheight = 480
    spec.visual.headlight.ambient = [0.4, 0.4, 0.4]
    tex = spec.add_texture(name="grid", type=mujoco.mjtTexture.mjTEXTURE_2D,
                           builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER, width=256, height=256,
                           rgb1=[0.32, 0.34, 0.38], rgb2=[0.26, 0.28, 0.31])
    mat = spec.add_material(name="grid", texrepeat=[8, 8], reflectance=0.1)
    mat.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = tex.name
    spec.worldbody.add_light(name="key", pos=[0.3, -0.3, 0.8], dir=[-0.3, 0.3, -0.8],
                             diffuse=[0.7, 0.7, 0.7])
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05],
                            material="grid", friction=[0.8, 0.005, 1e-4])
    spec.worldbody.add_camera(name="front", pos=[0, -0.45, 0.2], xyaxes=[1, 0, 0, 0, 0.3, 1])
    spec.worldbody.add_camera(name="side", pos=[0.45, 0, 0.2], xyaxes=[0, 1, 0, -0.3, 0, 1])


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
    add_element_meshes(spec, p)
    quat = np.zeros(4)
    rot = np.column_stack([[1, 0, 0], [0, 0, -1], [0, 1, 0]]).astype(float)
    mujoco.mju_mat2Quat(quat, rot.ravel())
    names = add_finger(spec, spec.worldbody, p, "f0", [0, 0, 0.1], quat, defaults)
    add_cable_drive(spec, p, names, defaults["servo"])
    spec.worldbody.add_camera(name="top", pos=[0.05, 0.03, 0.35], xyaxes=[1, 0, 0, 0, 1, 0])
    tune_soft_limits(spec, p)
    return spec
