"""One finger's blocked-tip force, any drive: the chain's statics against a stop at its tip.

**The setup: a one-sided stop, not a pinned tip.** One finger as the gripper builds it (its
drive's :meth:`gripper.drives.drive.Drive.add_finger`, its pads included) is clamped straight in
the world, gravity off; a frictionless plane through the tip's grasping-face edge (z = the
finger's height, normal towards the finger) blocks the tip's motion towards the grasping side
only (an explicit contact pair, so that only the tip element meets it; the tip may slide along
it as the finger curls). The drive is set to each command in turn (the cable drive's spool
angle [rad], the pneumatic drive's chamber pressure [Pa]; commands in order, each from the rest
of the one before) and held until the finger is at rest; the plane's normal force is the
blocked-tip force.

Why the stop: it is what the project reports as the "blocked-tip force per finger"
(``docs/contact.md``, "Forces a designer can read", the bound of ``scripts/force_bound.py``) and
what :mod:`gripper.calibration.contact_check` checks the cable chain against the continuum body
with (:func:`gripper.calibration.contact_check.tip_stop`): the force the finger presses on an
object in front of its tip. A tip pinned to the world (the design study's ``blocked_force`` up to
issue 58) also holds the tip along the finger, so its reaction mixes in the cable's axial pull
(at 5 % cable shortening on the default cable finger, 0.78 N along the finger against 0.08 N
towards the grasping side) and no reference checks it.

Paper 001's finite-element model carries no contact, so for the pneumatic finger the chain's
statics is the only figure (``tests/test_blocked_tip.py`` checks it against the chain's
small-angle statics by hand).

Example:
    >>> from gripper.core.params import GripperParams
    >>> p = GripperParams().replace(actuation=GripperParams().actuation.replace(kind="pneumatic"))
    >>> f = blocked_tip_force(p, [100e3])       # doctest: +SKIP
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

# Rest: forces and hinge angles are averaged over chunks of CHUNK_S (the cable finger's servo
# keeps a light blocked finger trembling at a few hundredths of a rad/s, its mean at rest); the
# finger is at rest when two chunks' means agree (REST_DEG, REST_FORCE), within MAX_S per command.
CHUNK_S = 0.5  # s: five of the pressure regulator's 0.1 s time constants
MAX_S = 10.0  # s of simulated time per command
REST_DEG = 2e-3  # deg: at rest when no hinge's chunk mean moves more than this ...
REST_FORCE = 2e-3  # -: ... and the mean stop force by less than this fraction


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


def _stop_force(m: mujoco.MjModel, d: mujoco.MjData, stop: int) -> float:
    force, total = np.zeros(6), 0.0
    for i in range(d.ncon):
        if stop in d.contact.geom[i]:
            mujoco.mj_contactForce(m, d, i, force)
            total += force[0]
    return total


def _hold(m: mujoco.MjModel, d: mujoco.MjData, stop: int, hinges: np.ndarray) -> float | None:
    """Step ``d`` in chunks until the finger is at rest (see ``REST_DEG``); the last chunk's mean
    stop force [N], or None when not at rest within ``MAX_S``."""
    n = int(round(CHUNK_S / m.opt.timestep))
    previous = None
    for _ in range(int(round(MAX_S / CHUNK_S))):
        forces, angles = np.zeros(n), np.zeros((n, len(hinges)))
        for k in range(n):
            mujoco.mj_step(m, d)
            forces[k], angles[k] = _stop_force(m, d, stop), d.qpos[hinges]
        check_stable(m, d, "blocked tip")
        mean_q, mean_f = np.degrees(angles.mean(axis=0)), float(forces.mean())
        if (previous is not None and np.abs(mean_q - previous[0]).max() < REST_DEG
                and abs(mean_f - previous[1]) <= REST_FORCE * max(abs(mean_f), 1e-12)):
            return mean_f
        previous = (mean_q, mean_f)
    return None


def blocked_tip_force(p: GripperParams, commands) -> np.ndarray:
    """The stop's normal force on the blocked tip at rest [N], one per drive command (in the
    drive's command unit: spool angle [rad] for the cable drive, chamber pressure [Pa] for the
    pneumatic; a cable shortening converts with :meth:`gripper.drives.drive.Drive.shortening_command`).
    The setup: the module docstring.

    Raises:
        ValueError: a command outside (0, the drive's command range].
        RuntimeError: the finger did not come to rest.
        SimulationUnstable: the finger went unstable.
    """
    commands = np.asarray(commands, dtype=float).reshape(-1)
    m, names = _scene(p)
    act = m.actuator(names.drive).id
    top = float(m.actuator_ctrlrange[act, 1])
    if not np.all((commands > 0) & (commands <= top)):
        raise ValueError(f"blocked_tip_force.commands: each must be in (0, {top:g}] for the "
                         f"{drive_for(p).kind} drive, got {commands.tolist()!r}")
    d = mujoco.MjData(m)
    stop = m.geom("stop").id
    hinges = np.array([m.jnt_qposadr[m.joint(h).id] for h in names.hinges])
    out = []
    for command in commands:
        d.ctrl[act] = command
        force = _hold(m, d, stop, hinges)
        if force is None:
            raise RuntimeError(f"blocked_tip_force: not at rest after {MAX_S:g} s at command {command:g}")
        out.append(force)
    return np.asarray(out)


__all__ = ["blocked_tip_force"]
