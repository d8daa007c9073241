"""Grasp objects: a latex balloon, a rigid block and cylinder, a card box, a plastic bag, user meshes.

Every object is sized to the default gripper's aperture: with straight fingers the grasping
faces stand 40 mm from the palm axis (palm radius), and trials offset the object by up to
±10 mm, so every object's horizontal half-extent (its half-diagonal where yaw is sampled) stays
at or below 28 mm. Heights stay below 70 mm so the palm clears the top with the fingertips
8 mm above the floor (finger length 96 mm).

Friction is the silicone–object pair coefficient. MuJoCo otherwise takes the larger of the
two geoms' coefficients, so object geoms and flexes carry ``priority`` 1 and their value is
the one used.

Deformable objects are MuJoCo flexes and need the ``discrete`` integrator (MuJoCo 4 integrates
flex elasticity only there, or with explicit Euler); grasp scenes use it for every object so
that all objects share one integrator.

Example:
    >>> from gripper.objects.library import get_object
    >>> obj = get_object("balloon")
    >>> obj.kind, obj.mass
    ('balloon', 0.004)
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import mujoco

from gripper.core.fields import Validated, param

OBJECT_BODY = "object"
CONTENTS_BODY = "object_contents"

# Height of the floor contact margin used when placing objects: objects start 1 mm above the
# floor and settle onto it during the protocol's settle phase.
DROP_GAP = 0.001


@dataclass(frozen=True)
class GraspObject(Validated):
    """One object of the library (SI units).

    Attributes:
        name: library name.
        kind: ``rigid_box``, ``rigid_cylinder``, ``balloon``, ``paper_box``, ``bag`` or ``mesh``.
        size: half-extents [m] (box: x, y, z; cylinder/balloon: radius, radius, half-height).
        mass: total mass [kg].
        friction: sliding friction coefficient against the silicone pads [-].
        yaw_symmetric: True where yaw does not change the grasp (no yaw is sampled).
        close_command: default servo closing set-point [rad of spool angle] (the object-specific
            closing command of the protocol).
        damage_limit: threshold of :attr:`damage_measure` above which the object is damaged.
        damage_measure: what is measured, with its unit.
        youngs_modulus: [Pa] for flexes (effective modulus for the balloon, see below).
        thickness: shell thickness [m] for 2D flexes.
        yield_strain: yield strain [-] of the paper box's card (ideal plasticity), in stretching
            and in bending alike: the same fibres yield whichever way they are strained.
        mesh_file: path of a user mesh (kind ``mesh``).
        notes: where the numbers come from.
    """

    name: str
    kind: str
    size: tuple[float, float, float]
    mass: float
    friction: float
    yaw_symmetric: bool
    close_command: float
    damage_limit: float
    damage_measure: str
    youngs_modulus: float = 0.0
    thickness: float = 0.0
    yield_strain: float = 0.0
    mesh_file: str = ""
    notes: str = ""

    @property
    def height(self) -> float:
        """Standing height [m]."""
        return 2.0 * self.size[2]

    @property
    def half_width(self) -> float:
        """Largest horizontal half-extent over all yaws [m]."""
        if self.kind in ("rigid_box", "paper_box", "mesh") and not self.yaw_symmetric:
            return math.hypot(self.size[0], self.size[1])
        return max(self.size[0], self.size[1])

    @property
    def is_flex(self) -> bool:
        return self.kind in ("balloon", "paper_box", "bag")

    def validate(self) -> GraspObject:
        for i, s in enumerate(self.size):
            if not (math.isfinite(s) and s > 0):
                raise ValueError(f"object.{self.name}.size[{i}]: must be > 0 m, got {s!r}")
        for field_name in ("mass", "friction", "close_command", "damage_limit"):
            v = getattr(self, field_name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise ValueError(f"object.{self.name}.{field_name}: must be > 0, got {v!r}")
        if self.half_width > 0.040:
            raise ValueError(f"object.{self.name}.size: horizontal half-extent {self.half_width:.3f} m "
                             "must be <= 0.040 m (the straight-finger aperture radius)")
        return self

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


# --- the default library -------------------------------------------------------------------

# Balloon. A small latex balloon inflated to Ø 56 mm (the largest sphere the aperture takes with
# ±10 mm placement noise). Latex envelope ≈ 2.5 g for a small balloon, air inside 1.2 kg/m³ ×
# 92 cm³ ≈ 0.1 g, its weight cancelled by buoyancy: 4 g total is used (mass of a small party
# balloon, weighed values are 2-5 g).
# Stiffness: an inflated balloon resists squeezing through its overpressure Δp; pressed by a
# flat plate to depth δ its contact force is F ≈ Δp · 2πRδ (flattened cap area), i.e. a
# stiffness 2πRΔp. Small latex balloons run at Δp ≈ 2-4 kPa (the pressure maximum of the
# balloon's inflation curve); 3 kPa at R = 0.028 m gives ≈ 530 N/m. The balloon is a 3D flex
# (tetrahedra to its centre, trilinear dofs) with an effective Young's modulus of 50 kPa, an
# assumption: pressed between the floor and a plate (gripper.experiments.crush, stiff flex contact, see
# FLEX_CONTACT_SOLREF) it takes 2.7 N at 6 mm and 4.8 N at 9 mm below its top, against 3.2 N
# and 4.8 N from F = 2πRΔp·δ.
# Burst: latex tears at an elongation of 700-800 % (stretch ≈ 8); an inflated balloon already
# runs at stretch ≈ 3-4, and stress concentrates where a finger edge presses. We count a burst
# when any surface edge of the flex stretches more than 25 % beyond its inflated length, a
# conservative limit (≈ one third of the remaining stretch margin 8/3.5 - 1 ≈ 1.3).
# Closing command 1.2 rad of spool: the fingers wrap the balloon and hold it with about 6 N in
# all (edge strain 0.05-0.11 on trials 0-9 of seed 0); 1.4 rad squeezed it to 0.09-0.13 and 1.6
# rad burst one trial of four, and the servo's full travel (3.0 rad) bursts every one (0.33-0.48).
BALLOON = GraspObject(
    name="balloon", kind="balloon", size=(0.028, 0.028, 0.028), mass=0.004, friction=1.0,
    yaw_symmetric=True, close_command=1.2, damage_limit=0.25,
    damage_measure="peak membrane edge strain [-] (burst above the limit)",
    youngs_modulus=5.0e4,
    notes="silicone on latex is grippy (μ ≈ 1); effective modulus see objects.py")

# Rigid parts are closed to 3.0 rad, near the end of the servo's travel (π) and past full finger
# closure (≈ 2.3 rad), so the servo stalls on the part and squeezes with its stall torque, as a
# hobby servo commanded past an obstacle does. At 2.2 rad the cylinder slipped out in the shake.
RIGID_CLOSE = 3.0

# Block: a rigid 40 × 40 × 60 mm part of 60 g (a PLA print at ~20 % infill: 96 cm³ × 1.24
# g/cm³ × ~0.5 effective fill). Silicone on PLA μ ≈ 0.6 (silicone on smooth plastics 0.5-0.8).
# Rigid parts take the servo's stall: their damage measure is the peak total contact force, with a
# limit (200 N) above what four 54 N cables press through fingers closed on their cut stops
# (peak totals up to 100 N in the 50-trial benchmark of 0.5.0, block and cylinder); a plastic part
# of this size fails at kilonewtons.
BLOCK = GraspObject(
    name="block", kind="rigid_box", size=(0.020, 0.020, 0.030), mass=0.060, friction=0.6,
    yaw_symmetric=False, close_command=RIGID_CLOSE, damage_limit=200.0,
    damage_measure="peak total contact force [N]")

# Cylinder: a rigid Ø 50 × 70 mm cylinder, 80 g (a plastic pill bottle with contents).
CYLINDER = GraspObject(
    name="cylinder", kind="rigid_cylinder", size=(0.025, 0.025, 0.035), mass=0.080, friction=0.6,
    yaw_symmetric=True, close_command=RIGID_CLOSE, damage_limit=200.0,
    damage_measure="peak total contact force [N]")

# Paper box: a 40 × 40 × 60 mm box of ≈ 170 g/m² card (≈ 0.2 mm thick, in-plane modulus
# ≈ 3 GPa; paperboard 2-6 GPa), lid closed; 20 g total (card ≈ 3 g plus light contents, lumped
# on the shell's vertices).
# Card is ideal-elastoplastic with one yield strain, 0.5 %, in stretching and in bending (the
# same fibres yield whichever way they are strained). Paperboard's stress-strain curve leaves
# linearity at 0.3-0.5 % strain and hardens to failure at 1.5-2 % in the machine direction
# (typical tensile curves, e.g. K. Niskanen (ed.), Paper Physics, 2008); with no hardening in
# the model, the yield sits at the top of that range. In-plane yield is what lets a finger dent
# a panel: pushed in by w over a half-span a, a panel stretches by about (w/a)^2/2, 0.5 % at
# w = 2 mm on a 40 mm face, while its bending strain stays small. Damage = a permanent dent
# deeper than 2 mm (a dent a customer sees on a retail box), measured after elastic
# spring-back (see trial.permanent_dent).
# Closing command 1.43 rad of spool (package 0.6.0, calibrated springs): 1.3 rad, chosen on the
# stiff 0.5.x springs, left the softer calibrated fingers resting on the box (median peak
# force 1 N, 1 of 11 held, seed 0); 1.43 rad held 10 of 10 undented (12-15 N, two yawed
# placements 120-128 N) while 1.625 and 1.95 rad dented 2 of 10 (2.0-2.6 mm). Chosen on seed 0,
# verified on seed 1 (docs/calibration.md).
PAPER_BOX_CLOSE = 1.43
PAPER_BOX = GraspObject(
    name="paper_box", kind="paper_box", size=(0.020, 0.020, 0.030), mass=0.020, friction=0.8,
    yaw_symmetric=False, close_command=PAPER_BOX_CLOSE, damage_limit=0.002,
    damage_measure="permanent dent depth after spring-back [m]",
    youngs_modulus=3.0e9, thickness=2.0e-4, yield_strain=0.005,
    notes="silicone on card μ ≈ 0.8")

# Bag: a 50 µm low-density polyethylene storage bag (E ≈ 200 MPa, LDPE 100-300 MPa), Ø 52 ×
# 70 mm sack, open at the top (flexcomp's open-top cylinder shell), film mass 3 g (50 µm ×
# 0.0135 m² × 920 kg/m³ ≈ 0.6 g, plus seams and zipper), holding a rigid 36 × 36 × 44 mm
# pack of 80 g; the fingers grasp the pack through the film. Damage = film tear: an edge of the
# film stretching beyond 10 % (LDPE yields at 10-15 % strain and necks beyond).
# Closing command 1.5 rad of spool: with the pack touching the film as stiffly as the fingers do
# (see _add_bag), the earlier 1.8 rad tore 3 of 50 films (strain 0.109-0.120, seed 0), while 1.5
# rad held 50 of 50 with no tear (film strain median 0.036, highest 0.096; about 120 N in all;
# 1.53 rad gave the same picture). Chosen on seed 0, the seed of the README's table.
BAG = GraspObject(
    name="bag", kind="bag", size=(0.026, 0.026, 0.035), mass=0.083, friction=0.6,
    yaw_symmetric=False, close_command=1.5, damage_limit=0.10,
    damage_measure="peak film edge strain [-] (tear above the limit)",
    youngs_modulus=2.0e8, thickness=5.0e-5,
    notes="film 3 g + contents 80 g; silicone on polyethylene μ ≈ 0.6")

BAG_FILM_MASS = 0.003  # kg, see BAG
BAG_CONTENTS_HALF = (0.018, 0.018, 0.022)  # m, the rigid pack inside the bag

LIBRARY: dict[str, GraspObject] = {o.name: o for o in (BALLOON, BLOCK, CYLINDER, PAPER_BOX, BAG)}
DEFAULT_OBJECTS = tuple(LIBRARY)


def get_object(name: str) -> GraspObject:
    """The library object ``name``, or a user mesh given as ``mesh:PATH[:MASS_KG]``.

    Raises:
        ValueError: unknown name (lists the allowed ones) or a bad mesh.
    """
    if name.startswith("mesh:"):
        rest = name[len("mesh:"):]
        path, _, mass = rest.partition("::") if "::" in rest else (rest, "", "")
        return mesh_object(path, mass=float(mass) if mass else None)
    if name not in LIBRARY:
        raise ValueError(f"objects: unknown object {name!r}; allowed: {', '.join(LIBRARY)} "
                         "or mesh:PATH")
    return LIBRARY[name]


# --- user meshes ---------------------------------------------------------------------------

# Density used for a user mesh given without a mass: a typical 3D-printed part (PLA 1240 kg/m³
# at about 50 % effective fill).
DEFAULT_MESH_DENSITY = 620.0


def load_mesh(path: str | Path, *, repair: bool = True):
    """Load an STL/OBJ/PLY with trimesh; repair small holes (with a warning) or refuse.

    Raises:
        ValueError: unreadable file, not a triangle mesh, or not watertight after repair.
    """
    import trimesh

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"mesh: file not found or unreadable: {path}")
    try:
        mesh = trimesh.load(path, force="mesh")
    except Exception as e:  # trimesh raises many types for malformed files
        raise ValueError(f"mesh: cannot read {path} as STL/OBJ/PLY ({e})") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ValueError(f"mesh: {path} holds no triangles")
    if not mesh.is_watertight:
        if repair:
            trimesh.repair.fill_holes(mesh)
            trimesh.repair.fix_normals(mesh)
        if not mesh.is_watertight:
            raise ValueError(f"mesh: {path} is not watertight (holes or open edges) and could not "
                             "be repaired; close it in a mesh editor")
        warnings.warn(f"mesh {path} was not watertight; holes filled by trimesh", stacklevel=2)
    if mesh.volume <= 0:
        mesh.invert()
    return mesh


def mesh_object(path: str | Path, *, mass: float | None = None, friction: float = 0.6,
                close_command: float = RIGID_CLOSE) -> GraspObject:
    """A rigid object from a user mesh (metres), centred on its bounding box, base on the floor.

    Mass from ``mass`` or from :data:`DEFAULT_MESH_DENSITY` × volume; inertia from the mesh
    (MuJoCo computes it from the same triangles); collision from its convex hull.
    """
    mesh = load_mesh(path)
    lo, hi = mesh.bounds
    hx, hy, hz = (float(v) for v in 0.5 * (hi - lo))
    half = (hx, hy, hz)
    m = float(mass) if mass is not None else DEFAULT_MESH_DENSITY * float(mesh.volume)
    obj = GraspObject(name=f"mesh:{path}", kind="mesh", size=half, mass=m, friction=friction,
                      yaw_symmetric=False, close_command=close_command, damage_limit=200.0,
                      damage_measure="peak total contact force [N]", mesh_file=str(path))
    return obj.validate()


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


def add_object(spec: mujoco.MjSpec, obj: GraspObject, place: Placement = Placement()) -> None:
    """Add ``obj`` to ``spec`` standing on the floor at ``place``; edits ``spec`` in place."""
    obj.validate()
    mass = obj.mass * place.mass_scale
    mu = obj.friction * place.friction_scale
    friction = [mu, 0.005, 1e-4]
    z = obj.size[2] + DROP_GAP
    pos = [place.x, place.y, z]
    quat = _yaw_quat(place.yaw)
    G = mujoco.mjtGeom
    if obj.kind in ("rigid_box", "rigid_cylinder", "mesh"):
        body = spec.worldbody.add_body(name=OBJECT_BODY, pos=pos, quat=quat)
        body.add_freejoint(name="object_free")
        if obj.kind == "rigid_box":
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_BOX, size=list(obj.size))
        elif obj.kind == "rigid_cylinder":
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_CYLINDER,
                                 size=[obj.size[0], obj.size[2], 0])
        else:
            mesh = load_mesh(obj.mesh_file)
            verts = mesh.vertices - 0.5 * (mesh.bounds[0] + mesh.bounds[1])
            spec.add_mesh(name="object_mesh", uservert=verts.ravel().tolist(),
                          userface=mesh.faces.ravel().tolist())
            geom = body.add_geom(name="object_geom", type=G.mjGEOM_MESH, meshname="object_mesh")
        geom.mass = mass
        geom.friction = friction
        geom.priority = 1
        geom.rgba = [0.2, 0.5, 0.8, 1.0]
        return
    if obj.kind == "balloon":
        _add_balloon(spec, obj, pos, mass, friction)
    elif obj.kind == "paper_box":
        _add_paper_box(spec, obj, pos, quat, mass, friction)
    elif obj.kind == "bag":
        _add_bag(spec, obj, pos, quat, mass, friction, place.mass_scale)
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


# Balloon mesh: flexcomp ellipsoid with 5 points per axis (99 surface vertices) on a trilinear
# 2 × 2 × 2 cell grid (81 dofs): enough for local dents under each finger at ≈ 1 ms a step.
BALLOON_COUNT = 5
BALLOON_CELLS = 2
# Rayleigh damping time of the balloon's elasticity [s]: latex and air damp the wobble within
# a few periods; 2 ms damps the 2 × 2 × 2 mode set without slowing the squeeze.
BALLOON_DAMPING = 0.002


def _add_balloon(spec, obj, pos, mass, friction) -> None:
    r = obj.size[0]
    spacing = 2.0 * r / (BALLOON_COUNT - 1)
    flex = spec.worldbody.make_flex(
        OBJECT_BODY, type="ellipsoid", dim=3, dof="trilinear", count=[BALLOON_COUNT] * 3,
        cellcount=[BALLOON_CELLS] * 3, spacing=[spacing] * 3, radius=0.0008, mass=mass,
        inertiabox=0.002, pos=pos)
    flex.young = obj.youngs_modulus
    # air in a closed balloon resists volume change far more than shape change
    flex.poisson = 0.45
    flex.damping = BALLOON_DAMPING
    flex.rgba = [0.85, 0.15, 0.2, 1.0]
    _flex_contact(flex, friction)


# Paper box shell: a closed box surface with 5 × 5 × 6 points per edge direction (10 × 10 ×
# 12 mm spacing), full dofs (bending plasticity needs a non-interpolated 2D flex). 4 × 4 × 5 was
# too coarse to bend under a finger. The shell is closed (lid on, as a product box): MuJoCo's
# flexcomp "box" shell is open at the top, and its free rim creased under light grasps (4 of 50
# default trials dented 2.1-3.5 mm at 3-8 N), which a closed carton's top face prevents.
PAPER_BOX_COUNT = (5, 5, 6)
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


def _add_paper_box(spec, obj, pos, quat, mass, friction) -> None:
    import tempfile

    mesh = box_shell(obj.size, PAPER_BOX_COUNT)
    # make_flex reads a mesh from a file; the shell is generated, written to a temporary OBJ
    with tempfile.TemporaryDirectory() as tmp:
        path = str(Path(tmp) / "paper_box_shell.obj")
        mesh.export(path)
        flex = spec.worldbody.make_flex(
            OBJECT_BODY, type="mesh", file=path, dim=2, dof="full", radius=0.001, mass=mass,
            inertiabox=0.002, pos=pos, quat=quat, elastic2d=3)
    flex.young = obj.youngs_modulus
    flex.poisson = PAPER_POISSON
    flex.thickness = obj.thickness
    flex.damping = PAPER_BOX_DAMPING
    flex.stressyield = [obj.yield_strain, obj.yield_strain]  # [stretching, bending]
    flex.rgba = [0.78, 0.65, 0.45, 1.0]
    _flex_contact(flex, friction)


BAG_COUNT = (5, 5, 6)
BAG_DAMPING = 0.002  # s, Rayleigh damping of the film: LDPE is lossy (tan δ ≈ 0.1)
PE_POISSON = 0.4  # LDPE 0.35-0.45


def _add_bag(spec, obj, pos, quat, mass, friction, mass_scale) -> None:
    r, _, hz = obj.size
    c = BAG_COUNT
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
