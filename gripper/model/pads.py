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
side of the contact is made near-rigid (``gripper.objects.scene_objects.RIGID_CONTACT_SOLREF``),
so the pad springs carry the indentation. The pad bottoms out at the silicone's depth above the
cable hole (cable) or the fabric (pneumatic): a joint limit. The element keeps its mass on a
collision-free copy of its body; the pad takes the mass of its silicone layer.

Grasp models step with MuJoCo's discrete integrator, implicit in the springs, so the stiff pad
springs on their light bodies are stable at the trials' 2 ms. Derivation and checks:
``docs/contact.md``.

Example:
    >>> from gripper.core.params import GripperParams
    >>> law = hertz_law(GripperParams())
    >>> round(float(law.indentation(2.0)) * 1e3, 2)      # mm under 2 N
    0.95
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.core.rounding import rounded_prism, rounded_sweep
from gripper.model.names import FingerNames
from gripper.objects.scene_objects import RIGID_CONTACT_SOLIMP, RIGID_CONTACT_SOLREF

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


def hertz_law(p: GripperParams) -> HertzLaw:
    """The pad's law for ``p``'s fingers: paper 000 Table 2's E and nu (cable), or paper 001's
    Yeoh fit at small strain, E = 6 C10 with nu = 0.5 (pneumatic)."""
    if p.pneumatic_fingers:
        e_star = 6.0 * p.material.yeoh_c10 / (1.0 - 0.5 ** 2)
    else:
        e_star = p.material.youngs_modulus / (1.0 - p.material.poisson_ratio ** 2)
    return HertzLaw(effective_modulus=e_star, radius=p.contact.pad_radius)


def pad_depth(p: GripperParams) -> float:
    """How far a pad can be pressed in before it bottoms out [m]: the silicone wall between the
    grasping face and the cable hole (cable), or between the face and the fabric's mid-plane
    (pneumatic: the neutral layer's height)."""
    if p.pneumatic_fingers:
        return p.pneumatic.neutral_height
    g = p.finger
    return g.height - g.hole_height - 0.5 * g.hole_diameter


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


def pad_spring(p: GripperParams) -> PadSpring:
    """The piecewise-linear interpolant of :func:`hertz_law` through the knots (see the module),
    up to ``contact.fit_force_max`` or the force at which the pad bottoms out (:func:`pad_depth`:
    11.2 N for the default cable finger, 7.1 N for the pneumatic one), whichever is lower; past
    it, the last chord's slope."""
    law = hertz_law(p)
    # up to the fit's top force or where the pad bottoms out, whichever comes first
    top = min(p.contact.fit_force_max, float(law.force(pad_depth(p))))
    n = max(1, math.ceil(math.log(top / KNOT_FORCE_MIN, KNOT_FORCE_RATIO)))
    forces = np.minimum(KNOT_FORCE_MIN * KNOT_FORCE_RATIO ** np.arange(n + 1), top)
    delta = np.concatenate([[0.0], law.indentation(forces)])
    f = np.concatenate([[0.0], forces])
    slopes = np.diff(f) / np.diff(delta)
    return PadSpring(knots=delta[:-1], stiffness=np.diff(np.concatenate([[0.0], slopes])))


def pad_damping(p: GripperParams, element_mass: float) -> float:
    """The pad joint's damping [N·s/m]: ``contact.damping_ratio`` of critical for the spring's
    tangent stiffness at 1 N on the element's mass."""
    law = hertz_law(p)
    k1 = 1.5 * 1.0 / float(law.indentation(1.0))
    return 2.0 * p.contact.damping_ratio * math.sqrt(k1 * element_mass)


# Mesh vertices are kept to the hull's corners and rounded to a micrometre, so the model files
# (gripper.sim.model_files) hold exactly the numbers the trials compile.
VERTEX_GRID = 1e-6  # m


def hull_vertices(points: np.ndarray) -> np.ndarray:
    """The convex hull's vertices of ``points``, on a :data:`VERTEX_GRID` grid [m]."""
    from scipy.spatial import ConvexHull

    grid = np.round(np.asarray(points, dtype=float) / VERTEX_GRID) * VERTEX_GRID
    return grid[ConvexHull(grid).vertices]


def cable_pad_vertices(p: GripperParams, profile: np.ndarray) -> np.ndarray:
    """A cable element's collision surface: its prism, every edge rounded to ``contact.edge_radius``.

    Raises:
        ValueError: naming ``contact.edge_radius``, when the rounding does not fit the element.
    """
    try:
        return hull_vertices(rounded_prism(profile, p.finger.width, p.contact.edge_radius))
    except ValueError as err:
        raise ValueError(f"contact.edge_radius: {p.contact.edge_radius!r} m does not fit this finger's "
                         f"elements ({err})") from None


def pneumatic_pad_vertices(p: GripperParams, section: np.ndarray, length: float) -> np.ndarray:
    """A pneumatic segment's collision surface: its section swept over its length, every edge
    (the section's corners and the end faces' rims) rounded to ``contact.pneumatic_edge_radius``
    (the round back is already round). The fingertip grasp runs the tip's end face along the
    table into the part, so its rim meets films first."""
    try:
        return hull_vertices(rounded_sweep(section, length, p.contact.pneumatic_edge_radius, round_ends=True))
    except ValueError as err:
        raise ValueError(f"contact.pneumatic_edge_radius: {p.contact.pneumatic_edge_radius!r} m does not fit "
                         f"this finger's segments ({err})") from None


def _convex_volume(vertices: np.ndarray) -> float:
    from scipy.spatial import ConvexHull

    return float(ConvexHull(vertices).volume)


class PadMaker:
    """Puts each element of one finger on its pad; the finger builders call it once per element
    (``gripper.model.builders.add_finger``, ``gripper.pneumatic.chamber.add_pneumatic_finger``).
    The meshes ``pad_{kind}`` come from :func:`add_pad_meshes`."""

    def __init__(self, spec: mujoco.MjSpec, p: GripperParams, names: FingerNames, defaults: dict):
        self.spec, self.p, self.names, self.defaults = spec, p, names, defaults
        self.spring = pad_spring(p)
        self.depth = pad_depth(p)

    def __call__(self, seg: mujoco.MjsBody, j: int, kind: str, collision: mujoco.MjsGeom,
                 element_vertices: np.ndarray, face_area: float) -> mujoco.MjsBody:
        """Element ``j`` (its body ``seg``, its collision geom ``collision``, its convex shape
        ``element_vertices`` and its grasping face's area [m²]) onto a pad; returns the pad body,
        where the element's touch site goes.

        The element's collision geom stops colliding and keeps the element's mass less the pad's;
        the pad body ``{prefix}_seg{j}_padbody`` slides along -z of the finger frame on
        ``{prefix}_seg{j}_padslide`` and carries the rounded collision mesh ``pad_{kind}``.
        """
        p, prefix = self.p, self.names.prefix
        element_mass = (p.material.density * _convex_volume(element_vertices)
                        if not math.isfinite(collision.mass) or collision.mass <= 0 else float(collision.mass))
        # the pad's own mass: the silicone layer of its depth under the grasping face
        pad_mass = min(0.5 * element_mass, p.material.density * face_area * self.depth)
        collision.contype = 0
        collision.conaffinity = 0
        collision.mass = element_mass - pad_mass
        pad = seg.add_body(name=f"{prefix}_seg{j}_padbody")
        slide = f"{prefix}_seg{j}_padslide"
        spring = self.spring
        pad.add_joint(name=slide, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0, 0, -1],
                      limited=mujoco.mjtLimited.mjLIMITED_TRUE, range=[-PAD_EXTENSION, self.depth],
                      stiffness=[float(spring.stiffness[0]), 0, 0], springref=0.0,
                      damping=[pad_damping(p, element_mass), 0, 0],
                      solref_limit=list(RIGID_CONTACT_SOLREF), solimp_limit=list(RIGID_CONTACT_SOLIMP))
        pad.add_geom(self.defaults["collision"], name=f"{prefix}_seg{j}_pad_collision",
                     type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"pad_{kind}", mass=pad_mass)
        for i in range(1, len(spring.knots)):
            ten = self.spec.add_tendon(name=f"{slide}_knot{i}", stiffness=[float(spring.stiffness[i]), 0, 0],
                                       springlength=[-1.0, float(spring.knots[i])])
            ten.wrap_joint(slide, 1.0)
        return pad

    def exclude_neighbours(self) -> None:
        """Neighbouring pads share the bridge, as their elements do; their contact is the hinge's
        limit (the closing cut), so their surfaces must not collide."""
        prefix = self.names.prefix
        for j in range(1, self.names.n_segments):
            self.spec.add_exclude(bodyname1=f"{prefix}_seg{j}_padbody", bodyname2=f"{prefix}_seg{j + 1}_padbody")


def add_pad_meshes(spec: mujoco.MjSpec, p: GripperParams) -> None:
    """The pads' rounded collision meshes, one per element kind (``pad_{kind}``)."""
    if p.pneumatic_fingers:
        from gripper.pneumatic.chamber import segment_section

        section = segment_section(p.pneumatic)
        for kind, length in (("half", 0.5 * p.pneumatic.pitch), ("full", p.pneumatic.pitch)):
            spec.add_mesh(name=f"pad_{kind}",
                          uservert=pneumatic_pad_vertices(p, section, length).ravel().tolist())
        return
    from gripper.model.geometry import element_kind, element_profile

    for kind in sorted({element_kind(i, p.finger.n_segments) for i in range(p.finger.n_segments)}):
        spec.add_mesh(name=f"pad_{kind}",
                      uservert=cable_pad_vertices(p, element_profile(p.finger, kind)).ravel().tolist())


__all__ = ["KNOT_FORCE_MIN", "KNOT_FORCE_RATIO", "PAD_EXTENSION", "VERTEX_GRID", "HertzLaw", "PadMaker",
           "PadSpring", "add_pad_meshes", "cable_pad_vertices", "hertz_law", "hull_vertices", "pad_damping",
           "pad_depth", "pad_spring", "pneumatic_pad_vertices"]
