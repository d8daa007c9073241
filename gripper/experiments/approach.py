"""The sensed approach: where the palm goes and which grasp it makes, from the palm camera's
estimate of the object (:mod:`gripper.sim.depth`) and the gripper's own kinematics only.

Two grasps:

- **envelope** (the benchmark's grasp since 0.1): the palm stops ``palm_clearance`` above the
  object's sensed top, or with the straight fingertips ``tip_clearance`` above the sensed
  support, whichever is higher, and the fingers curl around the object;
- **fingertip** (a surface-constrained grasp, as soft hands use the table to pick up low
  parts): the palm lowers the straight fingertips to ``fingertip_clearance`` above the sensed
  support (0 by default: onto it), and while the fingers close, it descends so that their
  lowest point stays at that clearance: the tips sweep inwards along the support and meet the
  object at its base. The
  descent follows the gripper's own free-closing kinematics (:func:`finger_reach`: how far below
  the palm the fingers reach at each spool angle, simulated once per design), never the object,
  and it stops ``palm_clearance`` above the sensed top.

The wrist (:func:`wrist_turn`, ``GraspProtocol.wrist``) turns the palm, during the approach, to
the sensed footprint's smallest enclosing rectangle: a finger onto its short axis, so that a
finger pair closes across a long part's width (a four-finger palm turns at most 45°). A part
longer than the opening (its half-length at least :func:`open_radius`) is *straddled*: its
long axis between two neighbouring fingers, which close on it from both sides, provided its
half-width leaves :data:`STRADDLE_MARGIN` to the fingers' nearest corners (:func:`straddle_gap`).

The rule (:func:`choose_grasp`), from geometry: the fingertip grasp when the straight
fingertips can reach the support beside the object, that is when the sensed top is at least
``palm_clearance`` below the palm at the fingertip grasp's start, and the sensed footprint's
extent along the fingers after the wrist's turn (half its length; its radius, the farthest
point from its centroid, when the wrist does not turn) stays ``fingertip_margin`` inside the
open fingers' grasping faces at the tips (:func:`open_radius`), or the part is straddled; otherwise
(a tall object, or one the tips would land on) the envelope. The palm is centred over the
sensed footprint's centroid (``GraspProtocol.centre``), clamped to the stage's travel.

Example:
    >>> from gripper.experiments.approach import GRASPS
    >>> GRASPS
    ('envelope', 'fingertip')
    >>> from gripper.core.params import GripperParams
    >>> round(straddle_gap(GripperParams()) * 1e3, 1)     # mm, at the default's open tips
    29.6
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.sim.depth import ObjectEstimate

GRASPS = ("envelope", "fingertip")
# How the turned palm meets the footprint: not turned, a finger across its width, or straddling it.
POSES = ("none", "across", "straddle")
# What a straddled part's side leaves to the open fingers' nearest corners [m] (assumed: room for
# the palm camera's width and centroid errors and for the fingers' sag; not measured).
STRADDLE_MARGIN = 0.003

# The settling time at each command of the free-closing reach's table (the commands are the
# drive's ``reach_commands``) [s]: holding each spool angle 0.8 s instead moves the table by at
# most 0.19 mm (reach below the palm) and 0.36 mm (closest approach to the axis), measured at the
# trials' 2 ms step.
REACH_SETTLE_S = 0.4
_REACH: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}


@dataclass(frozen=True)
class ApproachPlan:
    """Where the approach takes the palm (world frame, [m]) and which grasp follows.

    Attributes:
        grasp: ``envelope`` or ``fingertip``.
        x, y: palm position over the table.
        palm_z: palm-face height at the end of the approach.
        support_z: the support surface's height the plan was made for.
        floor_z: the lowest the palm face may go (``palm_clearance`` above the sensed top).
        yaw: the wrist's angle [rad].
        pose: how the fingers meet the footprint (:data:`POSES`).
    """

    grasp: str
    x: float
    y: float
    palm_z: float
    support_z: float
    floor_z: float = -math.inf
    yaw: float = 0.0
    pose: str = "none"


def open_radius(p: GripperParams) -> float:
    """How far the open, straight fingers' grasping faces stand from the palm axis at their tips
    [m]: the palm radius plus the finger's length times the sine of its splay
    (``layout.mount_tilt_deg``; 40 mm for a 40 mm palm whose fingers hang straight)."""
    return p.layout.palm_radius + drive_for(p).finger_length * math.sin(math.radians(p.layout.mount_tilt_deg))


def straddle_gap(p: GripperParams) -> float:
    """How far the open fingers' nearest corners stand, at their tips, from a line through the
    palm axis midway between two neighbouring fingers [m]: R sin(π/n) - (w/2) cos(π/n), R the
    :func:`open_radius`, n the fingers, w the finger's width (22.6 mm for a 40 mm opening and four
    16 mm fingers)."""
    n = p.layout.n_fingers
    return open_radius(p) * math.sin(math.pi / n) - 0.5 * drive_for(p).finger_width * math.cos(math.pi / n)


def check_fits_opening(obj, p: GripperParams):
    """``obj`` if the design ``p`` can take it: its footprint inside the open fingers
    (:func:`open_radius`), or a long part the wrist straddles (:func:`straddle_gap` less
    :data:`STRADDLE_MARGIN`), or an oversize object (``GraspObject.check_fits``).

    Raises:
        ValueError: one line naming the object, its size and this design's opening.
    """
    return obj.check_fits(open_radius(p), straddle_gap(p) - STRADDLE_MARGIN)


def wrist_turn(est: ObjectEstimate, p: GripperParams, proto) -> tuple[float, str]:
    """The wrist's angle [rad], in [-π/n, π/n), and the pose (:data:`POSES`) of the module
    docstring for the estimate ``est``."""
    if proto.wrist == "fixed" or not p.lift.yaw_enabled or p.layout.n_fingers < 2:
        return 0.0, "none"
    n = p.layout.n_fingers
    period = 2.0 * math.pi / n
    target = est.yaw + 0.5 * math.pi  # a finger on the short axis
    pose = "across"
    if 0.5 * est.length >= open_radius(p) and 0.5 * est.width + STRADDLE_MARGIN <= straddle_gap(p):
        target, pose = est.yaw + math.pi / n, "straddle"  # the long axis midway between two fingers
    yaw = (target + 0.5 * period) % period - 0.5 * period
    return float(yaw), pose


def choose_grasp(est: ObjectEstimate, p: GripperParams, proto, pose: str | None = None) -> str:
    """The rule of the module docstring; ``proto.grasp`` other than ``auto`` forces one.
    ``pose``: the wrist's (:func:`wrist_turn`'s, when not given)."""
    if proto.grasp != "auto":
        return proto.grasp
    if pose is None:
        pose = wrist_turn(est, p, proto)[1]
    drive = drive_for(p)
    tip = drive.fingertip_clearance(proto)
    clears_top = est.height + proto.palm_clearance <= drive.finger_length + tip
    reach = {"none": est.radius, "across": 0.5 * est.length, "straddle": 0.0}[pose]
    fits = reach < open_radius(p) - proto.fingertip_margin
    return "fingertip" if clears_top and fits else "envelope"


def plan_approach(est: ObjectEstimate, p: GripperParams, proto) -> ApproachPlan:
    """The plan of the module docstring for the estimate ``est``."""
    yaw, pose = wrist_turn(est, p, proto)
    grasp = choose_grasp(est, p, proto, pose)
    drive = drive_for(p)
    travel = p.lift.xy_travel
    x, y = (est.x, est.y) if proto.centre else (0.0, 0.0)
    x, y = float(np.clip(x, -travel, travel)), float(np.clip(y, -travel, travel))
    if grasp == "fingertip":
        z = est.support_z + drive.finger_length + drive.fingertip_clearance(proto)
    else:
        z = est.support_z + max(drive.finger_length + proto.tip_clearance, est.height + proto.palm_clearance)
    return ApproachPlan(grasp=grasp, x=x, y=y, palm_z=float(z), support_z=est.support_z,
                        floor_z=est.top_z + proto.palm_clearance, yaw=yaw, pose=pose)


def finger_reach(p: GripperParams) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fingers' free-closing reach: drive commands (the drive's ``reach_commands``: spool
    angles [rad], pressures [Pa], ...), how far below the palm face the lowest point of any finger is [m],
    and how close to the palm axis any finger comes [m].

    Simulated once per design and process (no object; each angle held until at rest, the
    grasp trials' integrator and step); the lowest point is taken over the element meshes'
    vertices.
    """
    key = stable_hash(p.to_dict())
    if key not in _REACH:
        _REACH[key] = _simulate_reach(p)
    return _REACH[key]


def _simulate_reach(p: GripperParams):
    from gripper.sim.scene import grasp_scene_spec

    spec = grasp_scene_spec(p)
    m = spec.compile()
    d = mujoco.MjData(m)
    drive = drive_for(p)
    actuators = drive.actuator_ids(m)
    palm = m.body("palm").id
    geoms = [g for g in range(m.ngeom) if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH
             and m.geom_contype[g] and m.body(m.geom_bodyid[g]).name.startswith("f")]
    mujoco.mj_forward(m, d)
    steps = int(round(REACH_SETTLE_S / m.opt.timestep))
    low, radial = [], []
    commands = drive.reach_commands()
    for a in commands:
        d.ctrl[actuators] = a
        for _ in range(steps):
            mujoco.mj_step(m, d)
        zs, rs = [], []
        for g in geoms:
            mid = m.geom_dataid[g]
            adr, n = m.mesh_vertadr[mid], m.mesh_vertnum[mid]
            v = m.mesh_vert[adr:adr + n] @ d.geom_xmat[g].reshape(3, 3).T + d.geom_xpos[g]
            zs.append(v[:, 2].min())
            rs.append(np.hypot(v[:, 0] - d.xpos[palm][0], v[:, 1] - d.xpos[palm][1]).min())
        low.append(d.xpos[palm][2] - min(zs))
        radial.append(min(rs))
    return commands, np.asarray(low), np.asarray(radial)


def fingertip_palm_z(plan: ApproachPlan, p: GripperParams, proto, command: np.ndarray) -> np.ndarray:
    """Palm-face height [m] that keeps the fingers' lowest point ``fingertip_clearance`` above
    the support at drive ``command`` values (the drive's unit: a spool angle [rad], a pressure [Pa];
    the deepest-reaching finger counts), never below ``plan.floor_z``."""
    commands, low, _ = finger_reach(p)
    reach = np.interp(command, commands, low)
    return np.maximum(plan.support_z + drive_for(p).fingertip_clearance(proto) + reach, plan.floor_z)

