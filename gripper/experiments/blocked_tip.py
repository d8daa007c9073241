"""The pneumatic finger's blocked-tip force: the chain's statics against a stop at its tip.

One pneumatic finger as the gripper builds it (its pads included) is clamped straight in the
world, gravity off; a frictionless plane through the tip's grasping-face edge blocks the tip's
motion towards the grasping side (an explicit contact pair, so that only the tip segment meets
it); the chamber is set to each pressure in turn and held until the finger is at rest; the
plane's normal force is the blocked-tip force. Paper 001's finite-element model carries no
contact, so the chain's statics is the only figure (the cable finger's, against the continuum
reference: :mod:`gripper.calibration.contact_check`).

Example:
    >>> from gripper.core.params import GripperParams
    >>> p = GripperParams().replace(actuation=GripperParams().actuation.replace(kind="pneumatic"))
    >>> f = blocked_tip_force_pneumatic(p, [100e3])       # doctest: +SKIP
"""

from __future__ import annotations

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.parts.defaults import add_defaults, set_options
from gripper.parts.names import FingerNames
from gripper.parts.pads import PadMaker, add_pad_meshes
from gripper.sim.stability import check_stable

SETTLE_S = 1.5  # s per pressure: fifteen of the regulator's 0.1 s time constants
REST_SPEED = 1e-4  # rad/s: every hinge slower than this at the end of a hold


def _scene(p: GripperParams) -> tuple[mujoco.MjModel, FingerNames]:
    drive = drive_for(p)
    spec = mujoco.MjSpec()
    set_options(spec, p)
    drive.configure(spec)
    spec.option.gravity = [0.0, 0.0, 0.0]
    defaults = add_defaults(spec, p)
    drive.add_defaults(spec, defaults)
    drive.add_meshes(spec)
    pads = p.contact.model == "pads"
    if pads:
        add_pad_meshes(spec, drive)
    maker = PadMaker(spec, drive, drive.names(0), defaults) if pads else None
    # finger frame = world frame: x along the finger, z towards the grasping face
    names = drive.add_finger(spec, spec.worldbody, 0, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], defaults, maker)
    if maker is not None:
        maker.exclude_neighbours()
    drive.tune(spec)
    n = names.n_segments
    stop = spec.worldbody.add_geom(name="stop", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0.05, 0.05, 0.01],
                                   pos=[drive.finger_length, 0.0, drive.finger_height], zaxis=[0.0, 0.0, -1.0],
                                   contype=0, conaffinity=0)
    tip = names.pad_collision(n) if pads else names.collision(n)
    spec.add_pair(geomname1=stop.name, geomname2=tip, condim=1, friction=[0, 0, 0, 0, 0])
    return spec.compile(), names


def blocked_tip_force_pneumatic(p: GripperParams, pressures) -> np.ndarray:
    """The stop's normal force on the blocked tip at rest [N], one per drive command (chamber
    pressures [Pa] for the pneumatic gripper, its use here; any drive's finger is built the same
    way, by its drive).

    Raises:
        ValueError: a command outside (0, the drive's command range].
        RuntimeError: the finger did not come to rest, or went unstable.
    """
    pressures = np.asarray(pressures, dtype=float)
    m, names = _scene(p)
    top = float(m.actuator_ctrlrange[m.actuator(names.drive).id, 1])
    if not np.all((pressures > 0) & (pressures <= top)):
        raise ValueError(f"blocked_tip_force_pneumatic.pressures: each must be in (0, {top:g}], "
                         f"got {pressures.tolist()!r}")
    d = mujoco.MjData(m)
    act = m.actuator(names.drive).id
    stop = m.geom("stop").id
    hinges = np.array([m.jnt_dofadr[m.joint(h).id] for h in names.hinges])
    steps = int(round(SETTLE_S / m.opt.timestep))
    out = []
    force = np.zeros(6)
    for pr in pressures:
        d.ctrl[act] = pr
        mujoco.mj_step(m, d, steps)
        check_stable(m, d, "blocked tip")
        if np.abs(d.qvel[hinges]).max() > REST_SPEED:
            raise RuntimeError(f"blocked_tip_force_pneumatic: not at rest after {SETTLE_S:g} s at {pr:g} Pa")
        total = 0.0
        for i in range(d.ncon):
            if stop in d.contact.geom[i]:
                mujoco.mj_contactForce(m, d, i, force)
                total += force[0]
        out.append(total)
    return np.asarray(out)


__all__ = ["blocked_tip_force_pneumatic"]
