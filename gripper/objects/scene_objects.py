"""Building a grasp object into a scene: where it stands (:class:`Placement`, the trial's
sampled perturbation) and its MJCF: a rigid geom or mesh, or a flex (the balloon's trilinear
cage, the box's and the bags' shells) with its contents.

Friction is the silicone–object pair coefficient. MuJoCo otherwise takes the larger of the
two geoms' coefficients, so object geoms and flexes carry ``priority`` 1 and their value is
the one used.

Deformable objects are MuJoCo flexes and need the ``discrete`` integrator (MuJoCo 4 integrates
flex elasticity only there, or with explicit Euler); grasp scenes use it for every object so
that all objects share one integrator.

Example:
    >>> import mujoco
    >>> from gripper.objects.library import get_object
    >>> from gripper.objects.scene_objects import Placement, add_object
    >>> spec = mujoco.MjSpec()
    >>> add_object(spec, get_object("block"), Placement(x=0.005))
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import mujoco

from gripper.core.fields import Validated, param
from gripper.objects.grasp_object import RIGID_KINDS, GraspObject, zipper_bag_layout
from gripper.objects.library import load_mesh

OBJECT_BODY = "object"
CONTENTS_BODY = "object_contents"

# Height of the floor contact margin used when placing objects: objects start 1 mm above the
# floor and settle onto it during the protocol's settle phase.
DROP_GAP = 0.001

# The bag's film mass and the rigid pack inside it (gripper/data/objects/bag.toml: 3 g of film,
# a 36 × 36 × 44 mm pack of 80 g).
BAG_FILM_MASS = 0.003  # kg
BAG_CONTENTS_HALF = (0.018, 0.018, 0.022)  # m


# --- building into a scene -----------------------------------------------------------------

@dataclass(frozen=True)
class Placement(Validated):
    """Where and how one trial's object is placed (the sampled perturbation).

    Attributes:
        x, y: offset of the object centre from the palm axis.
        yaw: rotation about the vertical.
        mass_scale, friction_scale: multipliers on the object's mass and friction.
    """

    SECTION = "placement"

    x: float = param(0.0, "m", source="centred under the palm")
    y: float = param(0.0, "m", source="centred under the palm")
    yaw: float = param(0.0, "rad", source="not rotated")
    mass_scale: float = param(1.0, "-", gt=0, source="the object's own mass")
    friction_scale: float = param(1.0, "-", gt=0, source="the object's own friction")


def _yaw_quat(yaw: float) -> list[float]:
    return [math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw)]


# A rigid part's contact when the fingers carry compliant pads (gripper.parts.pads): near-rigid,
# so the pads' springs, in N/m, carry the indentation. A contact's static stiffness is
# 1 / ((1 - d) A timeconst^2), A its inverse effective mass in the integrator's metric: with
# d = 0.999 and 4 ms (twice the trials' step, MuJoCo's stability floor) it is 2.7e5 N/m or more
# for A up to 230 kg⁻¹ (a 1 g pad on a 10 g part), about 100 times the pads' few thousand N/m.
# Fixed in seconds, not steps, so the contact is the same at every step size. The part's geom has
# priority, so these are the values its contacts use (with the floor too: a rigid part on a table).
RIGID_CONTACT_SOLREF = (0.004, 1.0)
RIGID_CONTACT_SOLIMP = (0.999, 0.999, 0.001, 0.5, 2.0)


def add_object(spec: mujoco.MjSpec, obj: GraspObject, place: Placement = Placement(), *,
               rigid_contact: bool = True) -> None:
    """Add ``obj`` to ``spec`` standing on the floor at ``place``; edits ``spec`` in place.
    ``rigid_contact``: a rigid part's contacts near-rigid (:data:`RIGID_CONTACT_SOLREF`), as the
    pads need; False keeps MuJoCo's default softness (0.16.0's ``contact.model = "solver"``)."""
    obj.validate()
    mass = obj.mass * place.mass_scale
    mu = obj.friction * place.friction_scale
    friction = [mu, 0.005, 1e-4]
    z = obj.size[2] + DROP_GAP
    pos = [place.x, place.y, z]
    quat = _yaw_quat(place.yaw)
    G = mujoco.mjtGeom
    if obj.kind in RIGID_KINDS:
        body = spec.worldbody.add_body(name=OBJECT_BODY, pos=pos, quat=quat)
        body.add_freejoint(name="object_free")
        if obj.kind == "rigid_box":
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_BOX, size=list(obj.size))
        elif obj.kind == "rigid_cylinder":
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_CYLINDER,
                                 size=[obj.size[0], obj.size[2], 0])
        elif obj.kind == "rigid_sphere":
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_SPHERE, size=[obj.size[0], 0, 0])
        else:
            mesh = load_mesh(obj.mesh_file)
            verts = mesh.vertices - 0.5 * (mesh.bounds[0] + mesh.bounds[1])
            spec.add_mesh(name="object_mesh", uservert=verts.ravel().tolist(),
                          userface=mesh.faces.ravel().tolist())
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_MESH, meshname="object_mesh")
        geom.mass = mass
        geom.friction = friction
        geom.priority = 1
        if rigid_contact:
            geom.solref = list(RIGID_CONTACT_SOLREF)
            geom.solimp = list(RIGID_CONTACT_SOLIMP)
        geom.rgba = [0.2, 0.5, 0.8, 1.0]
        return
    if obj.kind == "balloon":
        _add_balloon(spec, obj, pos, mass, friction)
    elif obj.kind == "paper_box":
        _add_paper_box(spec, obj, pos, quat, mass, friction)
    elif obj.kind == "bag":
        _add_bag(spec, obj, pos, quat, mass, friction, place.mass_scale)
    elif obj.kind == "zipper_bag":
        _add_zipper_bag(spec, obj, pos, place.yaw, friction, place.mass_scale)
    else:  # pragma: no cover - validate() and the library keep kinds closed
        raise ValueError(f"object.{obj.name}.kind: unknown kind {obj.kind!r}")


# Contact of deformable objects (with fingers, palm and floor; the flex has priority, so its values
# are used). MuJoCo's default contact (20 ms time constant, impedance 0.9-0.95) is stiff in
# proportion to the effective mass at the contact, and a flex spreads a few grams over ~100
# vertices: a plate pressing the 4 g balloon sank 10-20 mm into it and the balloon under it sank as
# far into the floor (gripper.experiments.crush), so the squeeze was taken by the contacts, not by the balloon's
# elasticity. Two steps of the trials' 2 ms (MuJoCo's stability floor; it clamps shorter time
# constants to two steps) and impedance 0.99-0.999 keep the sinking to 1-3 mm.
FLEX_CONTACT_SOLREF = (0.004, 1.0)
FLEX_CONTACT_SOLIMP = (0.99, 0.999, 0.001, 0.5, 2.0)


def _flex_contact(flex: mujoco.MjsFlex, friction: list[float]) -> None:
    flex.friction = friction
    flex.priority = 1
    flex.condim = 3
    flex.solref = list(FLEX_CONTACT_SOLREF)
    flex.solimp = list(FLEX_CONTACT_SOLIMP)
    flex.selfcollide = mujoco.mjtFlexSelf.mjFLEXSELF_NONE


# Balloon mesh: flexcomp ellipsoid with mesh_points surface points per axis (5: 99 vertices) on a
# trilinear 2 × 2 × 2 cell grid (81 dofs): enough for local dents under each finger.
BALLOON_CELLS = 2
# Rayleigh damping time of the balloon's elasticity [s]: latex and air damp the wobble within
# a few periods; 2 ms damps the 2 × 2 × 2 mode set without slowing the squeeze.
BALLOON_DAMPING = 0.002


def _add_balloon(spec, obj, pos, mass, friction) -> None:
    r = obj.size[0]
    pts = obj.mesh_points
    flex = spec.worldbody.make_flex(
        OBJECT_BODY, type="ellipsoid", dim=3, dof="trilinear", count=list(pts),
        cellcount=[BALLOON_CELLS] * 3, spacing=[2.0 * r / (n - 1) for n in pts], radius=0.0008, mass=mass,
        inertiabox=0.002, pos=pos)
    flex.young = obj.youngs_modulus
    # air in a closed balloon resists volume change far more than shape change
    flex.poisson = 0.45
    flex.damping = BALLOON_DAMPING
    flex.rgba = [0.85, 0.15, 0.2, 1.0]
    _flex_contact(flex, friction)


# Paper box shell: a closed box surface with mesh_points points per edge direction (5 × 5 × 6:
# 10 × 10 × 12 mm spacing), full dofs (bending plasticity needs a non-interpolated 2D flex).
# The shell is closed (lid on, as a product box): MuJoCo's
# flexcomp "box" shell is open at the top, and its free rim creased under light grasps (4 of 50
# default trials dented 2.1-3.5 mm at 3-8 N), which a closed carton's top face prevents.
# Rayleigh damping time [s] of the card: damps the shell's high modes at the 1 ms step.
PAPER_BOX_DAMPING = 0.001
# Paperboard Poisson ratio (0.2-0.4 in-plane).
PAPER_POISSON = 0.3


def box_shell(half: tuple[float, float, float], counts: tuple[int, int, int]):
    """A closed, watertight triangle mesh of a box surface (half-extents [m]) whose faces are
    grids of ``counts`` points along x, y, z, with outward normals (trimesh)."""
    import numpy as np
    import trimesh

    verts: list = []
    faces: list = []

    def face(origin, u, v, nu, nv):
        base = len(verts)
        for j in range(nv):
            for i in range(nu):
                verts.append(origin + u * i / (nu - 1) + v * j / (nv - 1))
        for j in range(nv - 1):
            for i in range(nu - 1):
                a = base + j * nu + i
                faces.extend([[a, a + 1, a + nu + 1], [a, a + nu + 1, a + nu]])

    hx, hy, hz = half
    cx, cy, cz = counts
    ex, ey, ez = np.eye(3)
    lo = np.array([-hx, -hy, -hz])
    # (u, v) ordered so that u × v points out of the box: every triangle winds outwards
    face(lo, 2 * hy * ey, 2 * hx * ex, cy, cx)                          # bottom (-z)
    face(np.array([-hx, -hy, hz]), 2 * hx * ex, 2 * hy * ey, cx, cy)    # top (+z)
    face(lo, 2 * hx * ex, 2 * hz * ez, cx, cz)                          # y- side
    face(np.array([-hx, hy, -hz]), 2 * hz * ez, 2 * hx * ex, cz, cx)    # y+ side
    face(lo, 2 * hz * ez, 2 * hy * ey, cz, cy)                          # x- side
    face(np.array([hx, -hy, -hz]), 2 * hy * ey, 2 * hz * ez, cy, cz)    # x+ side
    mesh = trimesh.Trimesh(np.array(verts), np.array(faces), process=True)  # merges shared edges
    if not (mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0):  # pragma: no cover
        raise RuntimeError("paper box shell is not a closed, outward-wound surface")
    return mesh


def _shell_flex(spec, obj, *, mass, pos, quat, radius, poisson, damping, rgba, friction) -> mujoco.MjsFlex:
    """A 2D flex over :func:`box_shell` of the object's size and mesh points, with its material
    (modulus, thickness) and the deformables' contact: the paper box's card, the zipper bag's
    film."""

    mesh = box_shell(obj.size, obj.mesh_points)
    # make_flex reads a mesh from a file; the shell is generated, written to a temporary OBJ
    with tempfile.TemporaryDirectory() as tmp:
        path = str(Path(tmp) / "shell.obj")
        mesh.export(path)
        flex = spec.worldbody.make_flex(
            OBJECT_BODY, type="mesh", file=path, dim=2, dof="full", radius=radius, mass=mass,
            inertiabox=0.002, pos=pos, quat=quat, elastic2d=3)
    flex.young = obj.youngs_modulus
    flex.poisson = poisson
    flex.thickness = obj.thickness
    flex.damping = damping
    flex.rgba = rgba
    _flex_contact(flex, friction)
    return flex


def _add_paper_box(spec, obj, pos, quat, mass, friction) -> None:
    flex = _shell_flex(spec, obj, mass=mass, pos=pos, quat=quat, radius=0.001, poisson=PAPER_POISSON,
                       damping=PAPER_BOX_DAMPING, rgba=[0.78, 0.65, 0.45, 1.0], friction=friction)
    flex.stressyield = [obj.yield_strain, obj.yield_strain]  # [stretching, bending]


BAG_DAMPING = 0.002  # s, Rayleigh damping of the film: LDPE is lossy (tan δ ≈ 0.1)
PE_POISSON = 0.4  # LDPE 0.35-0.45


def _add_bag(spec, obj, pos, quat, mass, friction, mass_scale) -> None:
    r, _, hz = obj.size
    c = obj.mesh_points
    film_mass = BAG_FILM_MASS * mass_scale
    flex = spec.worldbody.make_flex(
        OBJECT_BODY, type="cylinder", dim=2, dof="full", count=list(c),
        spacing=[2 * r / (c[0] - 1), 2 * r / (c[1] - 1), 2 * hz / (c[2] - 1)], radius=0.0007,
        mass=film_mass, inertiabox=0.002, pos=pos, quat=quat, elastic2d=3)
    flex.young = obj.youngs_modulus
    flex.poisson = PE_POISSON
    flex.thickness = obj.thickness
    flex.damping = BAG_DAMPING
    flex.rgba = [0.75, 0.85, 0.95, 0.6]
    _flex_contact(flex, friction)
    hx, hy, hcz = BAG_CONTENTS_HALF
    contents = spec.worldbody.add_body(name=CONTENTS_BODY, pos=[pos[0], pos[1], hcz + 0.0015],
                                       quat=quat)
    contents.add_freejoint(name="object_contents_free")
    g = contents.add_geom(name="object_contents_geom", type=mujoco.mjtGeom.mjGEOM_BOX,
                          size=[hx, hy, hcz], rgba=[0.8, 0.6, 0.2, 1.0])
    g.mass = mass - film_mass
    g.friction = friction
    g.priority = 1
    # The film's contact with the pack must be as stiff as its contact with the fingers: at equal
    # priority MuJoCo averages the two geoms' solref/solimp, and with the default on this side
    # (0.02 s) the pack sank 10-17 mm through the film's few-milligram vertices in every grasp,
    # and a film vertex popping back over a pack edge read as a 64 % "tear".
    g.solref = list(FLEX_CONTACT_SOLREF)
    g.solimp = list(FLEX_CONTACT_SOLIMP)


def _add_zipper_bag(spec, obj, pos, yaw, friction, mass_scale) -> None:
    """A closed zipper bag: a film shell (a box surface of the filled bag's size, as the paper
    box's, with the film's modulus and gauge) holding loose rigid items in one layer."""
    film_mass = (obj.mass - obj.contents_count * obj.contents_mass) * mass_scale
    quat = _yaw_quat(yaw)
    _shell_flex(spec, obj, mass=film_mass, pos=pos, quat=quat, radius=0.0007, poisson=PE_POISSON,
                damping=BAG_DAMPING, rgba=[0.75, 0.85, 0.95, 0.5], friction=friction)
    c, s_ = math.cos(yaw), math.sin(yaw)
    for k, (x, y, z) in enumerate(zipper_bag_layout(obj)):
        body = spec.worldbody.add_body(name=f"{CONTENTS_BODY}_{k}",
                                       pos=[pos[0] + c * x - s_ * y, pos[1] + s_ * x + c * y, pos[2] + z],
                                       quat=quat)
        body.add_freejoint(name=f"{CONTENTS_BODY}_{k}_free")
        g = body.add_geom(name=f"{CONTENTS_BODY}_{k}_geom", type=mujoco.mjtGeom.mjGEOM_BOX,
                          size=list(obj.contents_size), rgba=[0.85, 0.2, 0.15, 1.0])
        g.mass = obj.contents_mass * mass_scale
        g.friction = friction
        g.priority = 1
        g.solref = list(FLEX_CONTACT_SOLREF)  # as the bag's pack: as stiff against the film as the fingers
        g.solimp = list(FLEX_CONTACT_SOLIMP)
