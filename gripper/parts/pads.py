"""Compliant finger pads: the silicone's contact law in N/m, whatever the part weighs.

A MuJoCo contact's stiffness in N/m is its ``solref`` over the contact's inverse effective mass,
so no ``solref`` is a material: the same setting is ten times softer on a 6 g finger element than
on a 60 g part. Here the material's give lives in a joint instead. Each finger element (cable) or
segment (pneumatic) gets a ``pad`` body that slides into it along the grasping face's normal and
carries the element's collision surface (its edges rounded, :mod:`gripper.core.rounding`). The
pad's springs are in newtons per metre and follow Hertz's law for a rigid body of curvature
radius R pressed into the silicone,

    F = 4/3 E* sqrt(R) delta^(3/2),    E* = E / (1 - nu^2),

as a piecewise-linear spring (the pad joint's own stiffness from zero, then one dead-band
tendon spring per knot, MuJoCo's two-valued ``springlength``), knots at forces a factor
:data:`KNOT_FORCE_RATIO` apart from :data:`KNOT_FORCE_MIN` to ``contact.fit_force_max`` or to where
the pad bottoms out, whichever is lower. The part's
side of the contact is made near-rigid (``gripper.objects.kinds.rigid.RIGID_CONTACT_SOLREF``),
so the pad springs carry the indentation. The pad bottoms out at the silicone's depth above the
cable hole (cable) or the fabric (pneumatic): a joint limit. The element keeps its mass on a
collision-free copy of its body; the pad takes the mass of its silicone layer.

Grasp models step with MuJoCo's discrete integrator, implicit in the springs, so the stiff pad
springs on their light bodies are stable at the trials' 2 ms. Derivation and checks:
``docs/contact.md``.

Example:
    >>> from gripper.core.params import GripperParams
    >>> from gripper.drives import drive_for
    >>> law = hertz_law(drive_for(GripperParams()))
    >>> round(float(law.indentation(2.0)) * 1e3, 2)      # mm under 2 N
    0.95
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.objects.kinds.rigid import RIGID_CONTACT_SOLIMP, RIGID_CONTACT_SOLREF
from gripper.parts.names import FingerNames

# The spring's knots: Hertz's force at each, a factor KNOT_FORCE_RATIO apart from KNOT_FORCE_MIN.
# A chord of delta^(3/2) over a force ratio of 3 (an indentation ratio of 2.08) lies at most 5.1 %
# above it; the first chord, from zero to KNOT_FORCE_MIN, is below the 0.1 N the law is checked from.
KNOT_FORCE_MIN = 0.05  # N
KNOT_FORCE_RATIO = 3.0  # -

# How far a pad may be pulled out of its element [m] (a contact on the element's back pulls it).
PAD_EXTENSION = 0.0005


@dataclass(frozen=True)
class HertzLaw:
    """Hertz's force-indentation of a rigid body of curvature radius ``radius`` [m] pressed into
    a silicone half-space of plane-strain modulus ``effective_modulus`` [Pa]."""

    effective_modulus: float
    radius: float

    def force(self, delta):
        """Normal force [N] at indentation ``delta`` [m] (array or float)."""
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return 4.0 / 3.0 * self.effective_modulus * math.sqrt(self.radius) * d ** 1.5

    def indentation(self, force):
        """Indentation [m] under ``force`` [N]."""
        f = np.maximum(np.asarray(force, dtype=float), 0.0)
        return (f / (4.0 / 3.0 * self.effective_modulus * math.sqrt(self.radius))) ** (2.0 / 3.0)


def hertz_law(drive) -> HertzLaw:
    """The pad's law for a drive's fingers (:class:`gripper.drives.drive.Drive`: its
    ``contact_modulus``) and the design's ``contact.pad_radius``."""
    return HertzLaw(effective_modulus=drive.contact_modulus, radius=drive.params.contact.pad_radius)


@dataclass(frozen=True)
class PadSpring:
    """The piecewise-linear spring: stiffness ``stiffness[0]`` from zero, then ``stiffness[i]``
    more past ``knots[i]`` [N/m, m]."""

    knots: np.ndarray
    stiffness: np.ndarray

    def force(self, delta):
        """The spring's force [N] at compression ``delta`` [m]."""
        d = np.asarray(delta, dtype=float)[..., None]
        return np.sum(self.stiffness * np.maximum(d - self.knots, 0.0), axis=-1)


def pad_spring(drive) -> PadSpring:
    """The piecewise-linear interpolant of :func:`hertz_law` through the knots (see the module),
    up to ``contact.fit_force_max`` or the force at which the pad bottoms out (the drive's
    ``pad_depth``: 11.2 N for the default cable finger, 7.1 N for the pneumatic one), whichever is
    lower; past it, the last chord's slope."""
    law = hertz_law(drive)
    # up to the fit's top force or where the pad bottoms out, whichever comes first
    top = min(drive.params.contact.fit_force_max, float(law.force(drive.pad_depth)))
    n = max(1, math.ceil(math.log(top / KNOT_FORCE_MIN, KNOT_FORCE_RATIO)))
    forces = np.minimum(KNOT_FORCE_MIN * KNOT_FORCE_RATIO ** np.arange(n + 1), top)
    delta = np.concatenate([[0.0], law.indentation(forces)])
    f = np.concatenate([[0.0], forces])
    slopes = np.diff(f) / np.diff(delta)
    return PadSpring(knots=delta[:-1], stiffness=np.diff(np.concatenate([[0.0], slopes])))


def pad_damping(drive, element_mass: float) -> float:
    """The pad joint's damping [N·s/m]: ``contact.damping_ratio`` of critical for the spring's
    tangent stiffness at 1 N on the element's mass."""
    law = hertz_law(drive)
    k1 = 1.5 * 1.0 / float(law.indentation(1.0))
    return 2.0 * drive.params.contact.damping_ratio * math.sqrt(k1 * element_mass)


# Mesh vertices are kept to the hull's corners and rounded to a micrometre, so the model files
# (gripper.sim.model_files) hold exactly the numbers the trials compile.
VERTEX_GRID = 1e-6  # m


def hull_vertices(points: np.ndarray) -> np.ndarray:
    """The convex hull's vertices of ``points``, on a :data:`VERTEX_GRID` grid [m]."""
    from scipy.spatial import ConvexHull

    grid = np.round(np.asarray(points, dtype=float) / VERTEX_GRID) * VERTEX_GRID
    return grid[ConvexHull(grid).vertices]


def _convex_volume(vertices: np.ndarray) -> float:
    from scipy.spatial import ConvexHull

    return float(ConvexHull(vertices).volume)


class PadMaker:
    """Puts each element of one finger on its pad; a drive's finger builder calls it once per
    element (:meth:`gripper.drives.drive.Drive.add_finger`). The meshes ``pad_{kind}`` come from
    :func:`add_pad_meshes`."""

    def __init__(self, spec: mujoco.MjSpec, drive, names: FingerNames, defaults: dict):
        self.spec, self.drive, self.p, self.names, self.defaults = spec, drive, drive.params, names, defaults
        self.spring = pad_spring(drive)
        self.depth = drive.pad_depth

    def __call__(self, seg: mujoco.MjsBody, j: int, kind: str, collision: mujoco.MjsGeom,
                 element_vertices: np.ndarray, face_area: float) -> mujoco.MjsBody:
        """Element ``j`` (its body ``seg``, its collision geom ``collision``, its convex shape
        ``element_vertices`` and its grasping face's area [m²]) onto a pad; returns the pad body,
        where the element's touch site goes.

        The element's collision geom stops colliding and keeps the element's mass less the pad's;
        the pad body ``{prefix}_seg{j}_padbody`` slides along -z of the finger frame on
        ``{prefix}_seg{j}_padslide`` and carries the rounded collision mesh ``pad_{kind}``.
        """
        p = self.p
        element_mass = (p.material.density * _convex_volume(element_vertices)
                        if not math.isfinite(collision.mass) or collision.mass <= 0 else float(collision.mass))
        # the pad's own mass: the silicone layer of its depth under the grasping face
        pad_mass = min(0.5 * element_mass, p.material.density * face_area * self.depth)
        collision.contype = 0
        collision.conaffinity = 0
        collision.mass = element_mass - pad_mass
        names = self.names
        pad = seg.add_body(name=names.pad_body(j))
        slide = names.pad_slide(j)
        spring = self.spring
        pad.add_joint(name=slide, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0, 0, -1],
                      limited=mujoco.mjtLimited.mjLIMITED_TRUE, range=[-PAD_EXTENSION, self.depth],
                      stiffness=[float(spring.stiffness[0]), 0, 0], springref=0.0,
                      damping=[pad_damping(self.drive, element_mass), 0, 0],
                      solref_limit=list(RIGID_CONTACT_SOLREF), solimp_limit=list(RIGID_CONTACT_SOLIMP))
        pad.add_geom(self.defaults["collision"], name=names.pad_collision(j),
                     type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"pad_{kind}", mass=pad_mass)
        for i in range(1, len(spring.knots)):
            ten = self.spec.add_tendon(name=f"{slide}_knot{i}", stiffness=[float(spring.stiffness[i]), 0, 0],
                                       springlength=[-1.0, float(spring.knots[i])])
            ten.wrap_joint(slide, 1.0)
        return pad

    def exclude_neighbours(self) -> None:
        """Neighbouring pads share the bridge, as their elements do; their contact is the hinge's
        limit (the closing cut), so their surfaces must not collide."""
        for j in range(1, self.names.n_segments):
            self.spec.add_exclude(bodyname1=self.names.pad_body(j), bodyname2=self.names.pad_body(j + 1))


def add_pad_meshes(spec: mujoco.MjSpec, drive) -> None:
    """The pads' rounded collision meshes, one per element kind of the drive's finger (``pad_{kind}``)."""
    for kind in drive.pad_kinds():
        spec.add_mesh(name=f"pad_{kind}", uservert=drive.pad_vertices(kind).ravel().tolist())


__all__ = ["KNOT_FORCE_MIN", "KNOT_FORCE_RATIO", "PAD_EXTENSION", "VERTEX_GRID", "HertzLaw", "PadMaker",
           "PadSpring", "add_pad_meshes", "hertz_law", "hull_vertices", "pad_damping", "pad_spring"]
