"""The pneumatic finger in the MJCF: paper 001's actuator as a chain of rigid segments on hinges
at its neutral layer, bent by its chamber pressure through a fixed tendon, the pressure fed by a
proportional regulator (:mod:`gripper.datasheets.regulator`).

Structure (names ``f{k}_`` for finger k, as the cable finger's):

- ``seg1`` .. ``seg{n}``: a Hencky bar chain. The base ``seg1`` (on the root hinge at the clamp)
  and the tip ``seg{n}`` are half a pitch long, the others a full pitch
  ``length / (n - 1)``, so the n - 1 inner hinges sit at the middle of n - 1 equal parts of the
  length and a uniformly bent chain has its hinge points on the continuum's arc. Each segment is the
  actuator's cross-section (a half-disc back on a rectangle, convex) swept along its length.
- hinge ``hinge1`` at the clamp: the root's compliance, lumped (``root_stiffness``). In the
  finite-element reference the neutral layer turns sharply within the first few millimetres
  past the clamp (17° over the first 5 mm at 250 kPa, where the solid 5 mm end cap shears), then
  bends uniformly; a chain with no root hinge missed the tip by 4 % of the length at 250 kPa.
- hinge ``hinge{j}`` (j = 2..n) on the neutral layer's mid-plane (``PneumaticFinger.hinge_z``), so
  the fabric layer keeps its length however the finger bends; spring EI / pitch; damping
  ``damping_ratio`` of critical for that spring on the tip segment's inertia about its hinge
  (:func:`hinge_damping`; the root hinge takes the same damping).
- ``hinge{j}_stiffening``: a one-joint fixed tendon whose spring (``stiffening`` / pitch) acts only
  past the knee angle (``knee_curvature`` x pitch): a dead-band spring (MuJoCo's two-valued
  ``springlength``), the silicone and fibres stiffening as the actuator bends.
- the model steps with MuJoCo's discrete integrator (``gripper.drives.pneumatic.drive.PneumaticDrive.configure``): the
  short end segments on stiff hinges diverged under explicit springs at 1 ms.
- ``chamber``: a fixed tendon summing every hinge angle, driven by the actuator ``chamber``
  (``general``: its activation is the chamber pressure [Pa] behind the regulator's first-order
  lag, ``dyntype="filterexact"``; its gain the pressure's moment per pascal), so every hinge
  gets the same moment p x ``moment_per_pascal``: the section, and so the moment, is uniform.

Example:
    >>> import mujoco
    >>> from gripper.core.params import GripperParams
    >>> from gripper.model.builders import build_gripper_spec
    >>> p = GripperParams().replace(actuation=GripperParams().actuation.replace(kind="pneumatic"))
    >>> build_gripper_spec(p).compile().nu    # 4 chambers + 3 lift axes + the wrist
    8
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.core.params import GripperParams, PneumaticFinger
from gripper.parts.pads import VERTEX_GRID

# Points on the half-disc of each segment's cross-section (its round back).
BACK_POINTS = 13
# A hinge's range [rad]: backwards to the first contact of the round backs (assumed: 30°, a
# margin before neighbouring segments' 45° chamfer-free backs would meet), forwards far past the
# calibrated bend (the reference reaches 91° over seven hinges and the root, 13° each at most).
HINGE_RANGE = (-math.radians(30.0), math.radians(80.0))


def segment_vertices(pf: PneumaticFinger, length: float) -> np.ndarray:
    """Vertices of one segment's convex body in its frame [m]: the cross-section (y across, z from
    the back, the half-disc of radius width/2 centred at z = width/2, then straight sides down to
    the grasping face at z = height) at x = 0 and x = ``length``, on the pads' micrometre grid
    (:data:`gripper.parts.pads.VERTEX_GRID`), so the committed model file holds exactly the
    numbers the trials compile."""
    section = segment_section(pf)
    points = np.vstack([np.column_stack([np.full(len(section), x), section]) for x in (0.0, length)])
    return np.round(points / VERTEX_GRID) * VERTEX_GRID


def segment_section(pf: PneumaticFinger) -> np.ndarray:
    """The segment's cross-section (y, z) [m], counter-clockwise: the half-disc back of radius
    width/2 centred at z = width/2, then straight sides down to the grasping face at z = height."""
    r = 0.5 * pf.width
    phi = np.linspace(math.pi, 2.0 * math.pi, BACK_POINTS)
    back = np.column_stack([r * np.cos(phi), r + r * np.sin(phi)])
    return np.vstack([back, [[r, pf.height], [-r, pf.height]]])


def segment_lengths(pf: PneumaticFinger) -> list[float]:
    """Each segment's length [m]: half a pitch at the base and the tip, a pitch between."""
    return [0.5 * pf.pitch] + [pf.pitch] * (pf.n_segments - 2) + [0.5 * pf.pitch]


def add_segment_meshes(spec: mujoco.MjSpec, p: GripperParams) -> None:
    pf = p.pneumatic
    for kind, length in (("half", 0.5 * pf.pitch), ("full", pf.pitch)):
        spec.add_mesh(name=f"segment_{kind}", uservert=segment_vertices(pf, length).ravel().tolist())


def hinge_damping(pf: PneumaticFinger) -> float:
    """Each hinge's damping [N·m·s/rad]: ``damping_ratio`` of critical for its spring on the tip
    segment's inertia about its hinge (a half-pitch slab of the finger's mass per length, m l² / 3)."""
    m_tip = pf.mass * 0.5 * pf.pitch / pf.length
    inertia = m_tip * (0.5 * pf.pitch) ** 2 / 3.0
    return 2.0 * pf.damping_ratio * math.sqrt(pf.hinge_stiffness * inertia)


def add_pneumatic_finger(spec: mujoco.MjSpec, parent: mujoco.MjsBody, p: GripperParams, names,
                         pos, quat, defaults: dict, pad=None) -> None:
    """One pneumatic finger under ``parent`` (``pos``/``quat``: the finger frame in ``parent``'s),
    its chamber tendon and actuator and their sensors; ``names``: its
    :class:`gripper.parts.names.FingerNames`; ``pad``: a callable that puts each segment's surface
    on a compliant pad and returns the body its touch site goes on (``gripper.parts.pads.PadMaker``;
    None: the segment's own geom collides)."""
    pf = p.pneumatic
    lengths = segment_lengths(pf)
    damping = hinge_damping(pf)
    mount = parent.add_body(name=names.mount, pos=list(pos), quat=list(quat))
    body = mount
    for i, seg_len in enumerate(lengths):
        j = i + 1
        seg = body.add_body(name=names.body(j), pos=[lengths[i - 1] if i else 0.0, 0, 0])
        kind = "full" if 0 < i < len(lengths) - 1 else "half"
        hinge = names.hinge(j)
        if i == 0:  # the root: the clamp's compliance, lumped
            seg.add_joint(defaults.get("root_hinge", defaults["hinge"]), name=hinge,
                          pos=[0, 0, pf.hinge_z], range=list(HINGE_RANGE),
                          stiffness=[pf.root_stiffness, 0, 0], damping=[damping, 0, 0], springref=0.0)
        else:
            spec.add_exclude(bodyname1=body.name, bodyname2=seg.name)
            seg.add_joint(defaults.get("segment_hinge", defaults["hinge"]), name=hinge,
                          pos=[0, 0, pf.hinge_z], range=list(HINGE_RANGE),
                          stiffness=[pf.hinge_stiffness, 0, 0], damping=[damping, 0, 0], springref=0.0)
            stiff = spec.add_tendon(name=f"{hinge}_stiffening", stiffness=[pf.stiffening / pf.pitch, 0, 0],
                                    springlength=[-2.0 * math.pi, pf.knee_curvature * pf.pitch])
            stiff.wrap_joint(hinge, 1.0)
        mass = pf.mass * seg_len / pf.length
        seg.add_geom(defaults["visual"], name=names.visual(j), type=mujoco.mjtGeom.mjGEOM_MESH,
                     meshname=f"segment_{kind}", material="silicone")
        collision = seg.add_geom(defaults["collision"], name=names.collision(j),
                                 type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"segment_{kind}", mass=mass)
        host = seg if pad is None else pad(seg, j, kind, collision, segment_vertices(pf, seg_len), seg_len * pf.width)
        host.add_site(defaults["pad"], name=names.pad(j), pos=[0.5 * seg_len, 0, pf.height],
                     size=[0.5 * seg_len, 0.5 * pf.width, 0.0025])
        if j == pf.n_segments:
            seg.add_site(name=names.tip, pos=[seg_len, 0, pf.hinge_z], size=[0.001] * 3)
        body = seg
    add_chamber_drive(spec, p, names)


def add_hinge_defaults(spec: mujoco.MjSpec, defaults: dict, p: GripperParams) -> None:
    """The classes ``root_hinge`` and ``segment_hinge`` under ``hinge``: what the clamp's hinge and
    every inner hinge have on every finger (position on the neutral layer, range, spring, damper),
    stated once."""
    pf = p.pneumatic
    for name, stiffness in (("root_hinge", pf.root_stiffness), ("segment_hinge", pf.hinge_stiffness)):
        cls = spec.add_default(name, defaults["hinge"])
        cls.joint.pos = [0, 0, pf.hinge_z]
        cls.joint.range = list(HINGE_RANGE)
        cls.joint.stiffness = [stiffness, 0, 0]
        cls.joint.damping = [hinge_damping(pf), 0, 0]
        cls.joint.springref = 0.0
        defaults[name] = cls


def add_chamber_drive(spec: mujoco.MjSpec, p: GripperParams, names) -> None:
    """The chamber tendon (every hinge, coefficient 1), its actuator behind the regulator and the
    finger's sensors (hinge angles, the chamber's moment, pad touch)."""
    pf = p.pneumatic
    ds = pf.datasheet
    ten = spec.add_tendon(name=names.chamber)
    for h in names.hinges:
        ten.wrap_joint(h, 1.0)
    act = spec.add_actuator(name=names.drive, target=names.chamber, trntype=mujoco.mjtTrn.mjTRN_TENDON)
    act.dyntype = mujoco.mjtDyn.mjDYN_FILTEREXACT
    act.dynprm = [ds.time_constant] + [0.0] * 9
    act.gaintype = mujoco.mjtGain.mjGAIN_FIXED
    act.gainprm = [pf.moment_per_pascal] + [0.0] * 9
    act.biastype = mujoco.mjtBias.mjBIAS_NONE
    act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
    act.ctrlrange = [0.0, pf.command_max]
    act.actlimited = mujoco.mjtLimited.mjLIMITED_TRUE
    act.actrange = [0.0, pf.command_max]
    S = mujoco.mjtSensor
    for h in names.hinges:
        spec.add_sensor(name=f"{h}_angle", type=S.mjSENS_JOINTPOS, objname=h, objtype=mujoco.mjtObj.mjOBJ_JOINT)
    spec.add_sensor(name=f"{names.drive}_moment", type=S.mjSENS_ACTUATORFRC, objname=names.drive,
                    objtype=mujoco.mjtObj.mjOBJ_ACTUATOR)
    spec.add_sensor(name=f"{names.chamber}_bend", type=S.mjSENS_TENDONPOS, objname=names.chamber,
                    objtype=mujoco.mjtObj.mjOBJ_TENDON)
    for pad in names.pads:
        spec.add_sensor(name=pad, type=S.mjSENS_TOUCH, objname=pad, objtype=mujoco.mjtObj.mjOBJ_SITE)


__all__ = ["HINGE_RANGE", "add_chamber_drive", "add_hinge_defaults",
           "add_pneumatic_finger", "add_segment_meshes", "hinge_damping",
           "segment_lengths", "segment_section", "segment_vertices"]
