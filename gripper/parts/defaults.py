"""What every finger's model shares, whatever drives it: the default classes, the named
materials, the physics options and the rigid stop (a joint or tendon limit as stiff as the time
step allows).

Example:
    >>> import mujoco
    >>> from gripper.core.params import GripperParams
    >>> from gripper.parts.defaults import add_defaults
    >>> sorted(add_defaults(mujoco.MjSpec(), GripperParams()))
    ['collision', 'hinge', 'pad', 'root', 'visual']
"""

from __future__ import annotations

import mujoco

from gripper.core.params import GripperParams
from gripper.parts.names import MODEL_NAME

SILICONE_RGBA = (0.93, 0.93, 0.88, 1.0)
PALM_RGBA = (0.25, 0.27, 0.30, 1.0)
CABLE_RGBA = (0.85, 0.35, 0.10, 1.0)

# Touch-pad sites: thickness of the sensing slab on each grasping face [m]; it must hold the
# contact points of a few millimetres of penetration.
PAD_HALF_THICKNESS = 0.0025


# Shortest limit time constant, in time steps, of a rigid stop (and of every closure model of
# the cable finger): four steps held the stiffest stable stop under random commands (see
# add_defaults).
MIN_STEPS = 4.0
# Impedance of the rigid stop and of a linear closure stiffness (constant over the violation).
HINGE_LIMIT_IMPEDANCE = 0.9995
RIGID_STOP_SOLIMP = (HINGE_LIMIT_IMPEDANCE, HINGE_LIMIT_IMPEDANCE, 0.001, 0.5, 2.0)


def add_defaults(spec: mujoco.MjSpec, p: GripperParams, name: str = MODEL_NAME) -> dict[str, mujoco.MjsDefault]:
    """Menagerie-style default classes shared by every finger (root, visual, collision, hinge,
    pad) and the named materials the visual geoms and cables use; a drive adds its own classes
    (:meth:`gripper.drives.drive.Drive.add_defaults`)."""
    root = spec.add_default(name, spec.default)
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
    # hinge's time constant from the teeth's stiffness instead (gripper.drives.cable.closure).
    set_rigid_stop(hinge.joint, p)
    pad = spec.add_default("pad", root)
    pad.site.type = mujoco.mjtGeom.mjGEOM_BOX
    pad.site.group = 4
    pad.site.rgba = [0.1, 0.8, 0.1, 0.3]
    add_materials(spec)
    return {"root": root, "visual": visual, "collision": collision, "hinge": hinge, "pad": pad}


# Named materials of the visual geoms and the cables (Menagerie's grippers name theirs too).
MATERIALS = {"silicone": SILICONE_RGBA, "palm": PALM_RGBA, "cable": CABLE_RGBA}


def add_materials(spec: mujoco.MjSpec) -> None:
    for name, rgba in MATERIALS.items():
        spec.add_material(name=name, rgba=list(rgba))


def set_rigid_stop(owner, p: GripperParams) -> None:
    """A limit as stiff as the step allows (``MIN_STEPS`` steps, impedance 0.9995) on a joint
    default or a tendon."""
    owner.solref_limit = [MIN_STEPS * p.sim.timestep, 1.0]
    owner.solimp_limit = list(RIGID_STOP_SOLIMP)


def set_options(spec: mujoco.MjSpec, p: GripperParams) -> None:
    """The model's name, compiler settings and physics options, shared by every gripper (a drive
    may change its integrator: :meth:`gripper.drives.drive.Drive.configure`)."""
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
