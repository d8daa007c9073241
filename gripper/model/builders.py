"""Build the gripper (and its scenes) as a ``mujoco.MjSpec`` from :class:`GripperParams`: the palm
on its lift stage with one finger per mount, each built by the gripper's drive
(:func:`gripper.drives.drive_for`).

Structure of the cable gripper's model (names use ``f{k}_`` for finger k, elements 1-based as in
paper 000, B1 = ``seg1`` fixed to the palm; hinge ``hinge{j}`` joins ``seg{j-1}`` and ``seg{j}``
and carries spring M_j):

- ``palm`` on slide joints ``lift_x``, ``lift_y`` (optional) and ``lift_z`` and the wrist's
  hinge ``wrist_yaw`` about its axis (optional), each driven by a position actuator of the same
  name;
- per finger, a ``mount`` frame (finger frame, see :mod:`gripper.drives.cable.geometry`), the element chain,
  a ``reel`` body on a slide joint: the cable pulled onto the spool;
- per finger, a spatial tendon ``f{k}_cable`` from the reel through a site at each hole mouth to
  the tip anchor, limited to its straight-finger length: a rope (the limit is one-sided: it can
  go slack and never pushes);
- per finger, a ``dcmotor`` ``f{k}_servo`` on the reel joint with gear 1/spool radius, so the
  actuator length is the spool angle [rad] and its force the shaft torque [N·m];
- sensors: hinge angles, cable length and tension, servo angle and torque, pad touch forces.

The pneumatic gripper's fingers: :mod:`gripper.drives.pneumatic.chamber`.

Example:
    >>> import mujoco
    >>> from gripper import GripperParams, build_gripper_spec
    >>> model = build_gripper_spec(GripperParams()).compile()
    >>> model.nu    # 4 servos + 3 lift axes + the wrist
    8
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.core.params import DEG, GripperParams
from gripper.drives import Drive, drive_for
from gripper.objects.library import get_object
from gripper.parts.defaults import add_defaults, set_options
from gripper.parts.names import FingerNames
from gripper.parts.pads import PadMaker, add_pad_meshes

# The wrist: a rotary axis about the palm's axis (``lift.yaw_enabled``), its travel either side
# [rad]. A four-finger palm needs at most 45° to put a finger pair across any footprint; a
# quarter turn serves three fingers and more (assumed: a rotary stage's usual range).
WRIST = "wrist_yaw"
WRIST_TRAVEL = math.pi / 2


def add_fingers(spec: mujoco.MjSpec, parent: mujoco.MjsBody, drive: Drive, defaults: dict) -> list[FingerNames]:
    """Every finger on the palm, each with its actuator, as ``drive`` builds them."""
    p = drive.params
    out = []
    pads = p.contact.model == "pads"
    if pads:
        add_pad_meshes(spec, drive)
    for k in range(p.layout.n_fingers):
        pos, quat = finger_mount_pose(drive, k)
        maker = PadMaker(spec, drive, drive.names(k), defaults) if pads else None
        names = drive.add_finger(spec, parent, k, pos, quat, defaults, maker)
        if maker is not None:
            maker.exclude_neighbours()
        out.append(names)
    return out


def finger_mount_pose(drive: Drive, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Position and quaternion of finger ``k``'s frame in the palm frame.

    The palm frame has z up and its face at z = 0; finger x points down, the grasping face
    (finger z) looks at the palm axis, fingers evenly spaced by azimuth 2πk/n.
    """
    p = drive.params
    phi = 2.0 * math.pi * k / p.layout.n_fingers
    c, s = math.cos(phi), math.sin(phi)
    radial = p.layout.palm_radius + drive.finger_height
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
    drive = drive_for(p)
    spec = mujoco.MjSpec()
    set_options(spec, p)
    spec.modelname = drive.model_name
    drive.configure(spec)
    defaults = add_defaults(spec, p, drive.model_name)
    drive.add_defaults(spec, defaults)
    drive.add_meshes(spec)

    lift = p.lift
    palm = spec.worldbody.add_body(name="palm", pos=[0, 0, lift.home_height], childclass=drive.model_name)
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
    if lift.yaw_enabled:
        palm.add_joint(name=WRIST, type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1],
                       range=[-WRIST_TRAVEL, WRIST_TRAVEL], limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                       armature=0.0, damping=0.0)
    radius = p.layout.palm_radius + drive.finger_height + 0.004
    palm.add_geom(defaults["visual"], name="palm_visual", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                  size=[radius, 0.5 * p.layout.palm_thickness, 0],
                  pos=[0, 0, 0.5 * p.layout.palm_thickness], material="palm")
    palm.add_geom(defaults["collision"], name="palm_collision",
                  type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                  size=[radius, 0.5 * p.layout.palm_thickness, 0],
                  pos=[0, 0, 0.5 * p.layout.palm_thickness], mass=p.layout.palm_mass)
    palm.add_site(name="palm_center", pos=[0, 0, 0], size=[0.002] * 3)
    palm.add_camera(name="palm_cam", pos=[0, 0, -0.005], quat=[0, 1, 0, 0], fovy=90)

    add_fingers(spec, palm, drive, defaults)

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
    if lift.yaw_enabled:
        add_wrist_actuator(spec, p, radius)
    spec.add_sensor(name="palm_pos", type=mujoco.mjtSensor.mjSENS_FRAMEPOS, objname="palm_center",
                    objtype=mujoco.mjtObj.mjOBJ_SITE)
    drive.tune(spec)
    if p.contact.model == "pads":
        # The pads' stiff springs on light bodies need MuJoCo's discrete integrator, implicit in
        # the springs (gripper.parts.pads), as the grasp scenes take anyway; set after the limits
        # are tuned, whose match to that integrator the grasp scenes make once per design
        # (gripper.sim.scene).
        spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    return spec


def add_wrist_actuator(spec: mujoco.MjSpec, p: GripperParams, palm_radius: float) -> None:
    """The wrist's position actuator and its angle sensor: gain ``lift.yaw_stiffness``, damped
    at the linear axes' ratio on the palm disc's inertia about its axis (m r² / 2; the fingers
    add to it, so the wrist is somewhat less damped than stated)."""
    lift = p.lift
    inertia = 0.5 * p.layout.palm_mass * palm_radius ** 2
    act = spec.add_actuator(name=WRIST, target=WRIST, trntype=mujoco.mjtTrn.mjTRN_JOINT)
    act.set_to_position(kp=lift.yaw_stiffness, kv=2.0 * lift.damping_ratio * math.sqrt(lift.yaw_stiffness * inertia))
    act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
    act.ctrlrange = [-WRIST_TRAVEL, WRIST_TRAVEL]
    act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
    act.forcerange = [-lift.yaw_max_torque, lift.yaw_max_torque]
    spec.add_sensor(name=f"{WRIST}_pos", type=mujoco.mjtSensor.mjSENS_JOINTPOS, objname=WRIST,
                    objtype=mujoco.mjtObj.mjOBJ_JOINT)


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
