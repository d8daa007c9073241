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

from gripper.core.fields import Validated, check_safe_name, param
from gripper.core.resources import OBJECTS_DIR

OBJECT_BODY = "object"
CONTENTS_BODY = "object_contents"

# Height of the floor contact margin used when placing objects: objects start 1 mm above the
# floor and settle onto it during the protocol's settle phase.
DROP_GAP = 0.001


# Damage criteria: what is measured, its unit, and the kinds it applies to.
DAMAGE_CRITERIA = {
    "strain": ("peak edge strain of the membrane or film [-] (burst or tear above the limit)",
               ("balloon", "bag", "zipper_bag")),
    "dent": ("permanent dent depth after spring-back [m]", ("paper_box",)),
    "contact_force": ("peak total contact force [N]", ("rigid_box", "rigid_cylinder", "rigid_sphere", "mesh")),
    "none": ("not damaged by grasping", ("rigid_box", "rigid_cylinder", "rigid_sphere", "mesh")),
}
RIGID_KINDS = ("rigid_box", "rigid_cylinder", "rigid_sphere", "mesh")
KINDS = (*RIGID_KINDS, "balloon", "paper_box", "bag", "zipper_bag")
# The deformable kinds' default mesh resolution (points along x, y, z; GraspObject.mesh_points),
# where each one's convergence check put it (docs/performance.md, "Mesh resolution"):
# - balloon: 5 surface points per axis (99 vertices) on a 2 x 2 x 2 trilinear cage (81 dofs);
# - paper box: 5 x 5 x 6 points (10 x 10 x 12 mm spacing, 114 vertices); 4 x 4 x 5 would halve
#   its cost and keep the benchmark's outcomes, but its faces are 23-53 % stiffer under a finger;
# - bag: 4 x 4 x 5 points (64 vertices: film elements of about 17 mm), half the cost of 5 x 5 x 6
#   with the outcome and the strain inside the 4 / 5 / 6-point spread;
# - zipper bag: 6 x 4 x 3 points (about 10 x 7.5 x 8 mm film elements; docs/objects.md).
DEFAULT_MESH_POINTS = {"balloon": (5, 5, 5), "paper_box": (5, 5, 6), "bag": (4, 4, 5), "zipper_bag": (6, 4, 3)}
# Allowed resolutions: flexcomp needs 3 points an axis for a closed surface; 12 is a 10-fold cost.
MESH_POINTS_RANGE = (3, 12)
# The open fingers' grasping faces stand this far from the palm axis in the default design
# (layout.palm_radius): an object's horizontal footprint must fit inside [m].
APERTURE_RADIUS = 0.040


@dataclass(frozen=True)
class GraspObject(Validated):
    """One grasp object (SI units), from an object file (:mod:`gripper.objects.files`).

    Attributes:
        name: the object's name, as trial records give it.
        kind: ``rigid_box``, ``rigid_cylinder``, ``rigid_sphere``, ``mesh`` (rigid, from a user
            mesh), or one of
            the deformable kinds the project models: ``balloon``, ``paper_box``, ``bag``.
        size: half-extents [m] (box: x, y, z; cylinder/balloon: radius, radius, half-height;
            sphere: radius three times).
        mass: total mass [kg].
        friction: sliding friction coefficient against the silicone pads [-].
        yaw_symmetric: True where yaw does not change the grasp (no yaw is sampled).
        close_command: servo closing set-point [rad of spool angle] (the object-specific
            closing command of the protocol).
        damage: the damage criterion (:data:`DAMAGE_CRITERIA`): ``strain``, ``dent``,
            ``contact_force`` or ``none``.
        damage_limit: threshold of the criterion's measure above which the object is damaged.
        youngs_modulus: [Pa] for flexes (effective modulus for the balloon).
        thickness: shell thickness [m] for 2D flexes.
        yield_strain: yield strain [-] of the paper box's card (ideal plasticity), in stretching
            and in bending alike.
        mesh_file: path of the mesh (kind ``mesh``).
        footprint_radius: radius of the mesh hull's horizontal footprint about its centre [m]
            (kind ``mesh``; 0 for the primitives, whose footprint follows from ``size``).
        oversize: the object may be wider than the open fingers (the capability envelope's
            largest sizes: the fingers then land on it); off for library and user objects.
        mesh_points: the deformable kinds' mesh resolution, points along x, y, z (the flexcomp's
            ``count``; the balloon's surface points per axis); (0, 0, 0) for the rigid kinds.
            The deformables default to :data:`DEFAULT_MESH_POINTS` (their convergence check is
            in ``docs/performance.md``).
        contents_count, contents_size, contents_mass: a zipper bag's loose contents: how many
            rigid items, each one's half-extents [m] and mass [kg] (``mass`` is the film's and
            the items' together).
        reasons: (field, reason) pairs: where the numbers come from (not part of the physics,
            so not part of :meth:`to_dict`).
    """

    name: str
    kind: str
    size: tuple[float, float, float]
    mass: float
    friction: float
    yaw_symmetric: bool
    close_command: float
    damage: str
    damage_limit: float
    youngs_modulus: float = 0.0
    thickness: float = 0.0
    yield_strain: float = 0.0
    mesh_file: str = ""
    footprint_radius: float = 0.0
    oversize: bool = False
    mesh_points: tuple[int, int, int] = (0, 0, 0)
    contents_count: int = 0
    contents_size: tuple[float, float, float] = (0.0, 0.0, 0.0)
    contents_mass: float = 0.0
    reasons: tuple[tuple[str, str], ...] = dataclasses.field(default=(), compare=False)

    @property
    def height(self) -> float:
        """Standing height [m]."""
        return 2.0 * self.size[2]

    @property
    def half_width(self) -> float:
        """Largest horizontal distance of the object from its centre over all yaws [m]: the
        mesh hull's footprint radius, the box's half-diagonal (its corners sweep a circle when
        yaw is sampled), or the round objects' radius."""
        if self.kind == "mesh" and self.footprint_radius > 0:
            return self.footprint_radius
        if self.kind in ("rigid_box", "paper_box", "mesh", "zipper_bag") and not self.yaw_symmetric:
            return math.hypot(self.size[0], self.size[1])
        return max(self.size[0], self.size[1])

    @property
    def is_flex(self) -> bool:
        return self.kind in ("balloon", "paper_box", "bag", "zipper_bag")

    @property
    def damage_measure(self) -> str:
        """What the damage criterion measures, with its unit."""
        return DAMAGE_CRITERIA[self.damage][0]

    def is_damaged(self, measure: float) -> bool:
        """Whether ``measure`` (of :attr:`damage`) exceeds the limit; never for ``none``."""
        return self.damage != "none" and measure > self.damage_limit

    def validate(self) -> GraspObject:
        if isinstance(self.name, str) and self.name.startswith("mesh:"):
            _check_mesh_spec(self.name)
        else:
            check_safe_name(self.name, "object.name")
        where = f"object.{self.name}"
        if self.kind not in KINDS:
            raise ValueError(f"{where}.kind: must be one of {', '.join(KINDS)}, got {self.kind!r}")
        for i, s in enumerate(self.size):
            if not (isinstance(s, int | float) and math.isfinite(s) and s > 0):
                raise ValueError(f"{where}.size[{i}]: must be > 0 m, got {s!r}")
        for field_name in ("mass", "friction", "close_command"):
            v = getattr(self, field_name)
            if isinstance(v, bool) or not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise ValueError(f"{where}.{field_name}: must be > 0, got {v!r}")
        if self.damage not in DAMAGE_CRITERIA or self.kind not in DAMAGE_CRITERIA[self.damage][1]:
            allowed = [c for c, (_, kinds) in DAMAGE_CRITERIA.items() if self.kind in kinds]
            raise ValueError(f"{where}.damage: a {self.kind} allows {', '.join(allowed)}, got {self.damage!r}")
        v = self.damage_limit
        if self.damage != "none" and (isinstance(v, bool) or not (isinstance(v, int | float)
                                                                 and math.isfinite(v) and v > 0)):
            raise ValueError(f"{where}.damage_limit: must be > 0, got {v!r}")
        pts = self.mesh_points
        if not (isinstance(pts, tuple) and len(pts) == 3
                and all(isinstance(n, int) and not isinstance(n, bool) for n in pts)):
            raise ValueError(f"{where}.mesh_points: must be three whole numbers, got {pts!r}")
        if self.is_flex and not all(MESH_POINTS_RANGE[0] <= n <= MESH_POINTS_RANGE[1] for n in pts):
            raise ValueError(f"{where}.mesh_points: a {self.kind} takes {MESH_POINTS_RANGE[0]} to "
                             f"{MESH_POINTS_RANGE[1]} points along each axis, got {list(pts)}")
        if not self.is_flex and pts != (0, 0, 0):
            raise ValueError(f"{where}.mesh_points: a {self.kind} is rigid and has no mesh resolution, "
                             f"got {list(pts)}")
        if self.kind == "zipper_bag":
            zipper_bag_layout(self)  # raises if the contents do not fit or outweigh the bag
        elif self.contents_count:
            raise ValueError(f"{where}.contents: only a zipper_bag holds loose contents, this is a {self.kind}")
        if self.kind == "rigid_sphere" and not (self.size[0] == self.size[1] == self.size[2]):
            raise ValueError(f"{where}.size: a sphere's three half-extents are its radius, got {list(self.size)}")
        if self.half_width > APERTURE_RADIUS and not self.oversize:
            what = "hull footprint radius" if self.kind == "mesh" and self.footprint_radius > 0 else \
                "horizontal half-extent"
            raise ValueError(f"{where}.size: its {what} is {self.half_width:.3f} m over all yaws; the open "
                             f"fingers of the default design leave {APERTURE_RADIUS:.3f} m: scale the object "
                             "down (a round part: declare it yaw_symmetric, so its radius counts)")
        return self

    def to_dict(self) -> dict:
        """The physics of the object (everything but :attr:`reasons`; the contents only where
        there are some), JSON-ready."""
        skip = {"reasons"}
        if not self.contents_count:
            skip |= {"contents_count", "contents_size", "contents_mass"}
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name not in skip}


# --- the default library -------------------------------------------------------------------

# The rigid objects' closing command: near the end of the servo's travel (π) and past full finger
# closure (≈ 2.3 rad), so the servo stalls on the part and squeezes with its stall torque
# (gripper/data/objects/block.toml gives the reason); user meshes default to it.
RIGID_CLOSE = 3.0

# The bag's film mass and the rigid pack inside it (gripper/data/objects/bag.toml: 3 g of film,
# a 36 × 36 × 44 mm pack of 80 g).
BAG_FILM_MASS = 0.003  # kg
BAG_CONTENTS_HALF = (0.018, 0.018, 0.022)  # m

DEFAULT_OBJECTS = ("balloon", "block", "cylinder", "paper_box", "bag")
# Shipped object files beyond the benchmark's five, by name: the pack-in-a-bag of 0.11.0 and
# before (a hard case, docs/limitations.md).
EXTRA_OBJECTS = ("bag_pack",)


def _library() -> dict[str, GraspObject]:
    from gripper.objects.files import load_object_file

    return {name: load_object_file(OBJECTS_DIR / f"{name}.toml") for name in (*DEFAULT_OBJECTS, *EXTRA_OBJECTS)}


LIBRARY: dict[str, GraspObject] = {}  # filled on first use (the object files are package data)


def library() -> dict[str, GraspObject]:
    """The built-in objects (the default five and :data:`EXTRA_OBJECTS`), read once from their
    object files in ``gripper/data/objects``."""
    if not LIBRARY:
        LIBRARY.update(_library())
    return LIBRARY


MESH_SPEC_MAX = 255  # characters of a ``mesh:PATH[::MASS]`` name, a file system's name limit


def _check_mesh_spec(spec: str) -> None:
    """A ``mesh:`` spec names its records: printable, one line, at most :data:`MESH_SPEC_MAX`."""
    if len(spec) > MESH_SPEC_MAX or not spec.isprintable():
        raise ValueError(f"objects: a mesh:PATH name must be printable and at most {MESH_SPEC_MAX} "
                         f"characters, got {len(spec)} characters")


def get_object(spec: str) -> GraspObject:
    """The object ``spec`` names: a built-in name, an object file (``.toml`` or ``.json``), or a
    user mesh as ``mesh:PATH`` or ``mesh:PATH::MASS_KG``. Records name the object by
    :attr:`GraspObject.name`: the built-in's name, the file's ``object.name``, or the ``mesh:``
    spec exactly as given.

    Raises:
        ValueError: unknown name (lists the allowed ones), a bad file or a bad mesh.
    """
    if not isinstance(spec, str) or not spec:
        raise ValueError(f"objects: expected an object name, file or mesh:PATH, got {spec!r}")
    if spec.startswith("mesh:"):
        rest = spec[len("mesh:"):]
        path, sep, mass_text = rest.partition("::")
        mass = None
        if sep:
            try:
                mass = float(mass_text)
            except ValueError:
                raise ValueError(f"objects: {spec}: the mass after '::' must be a number in kg, "
                                 f"got {mass_text!r}") from None
        return dataclasses.replace(mesh_object(path, mass=mass), name=spec).validate()
    if spec.endswith((".toml", ".json")):
        from gripper.objects.files import load_object_file

        return load_object_file(spec)
    lib = library()
    if spec not in lib:
        raise ValueError(f"objects: unknown object {spec!r}; allowed: {', '.join(lib)}, an object "
                         "file (.toml or .json) or mesh:PATH[::MASS]")
    return lib[spec]


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


def mesh_object(path: str | Path, *, mass: float | None = None, density: float | None = None,
                friction: float = 0.6, close_command: float = RIGID_CLOSE, damage: str = "contact_force",
                damage_limit: float = 200.0, yaw_symmetric: bool = False, name: str | None = None,
                reasons: tuple[tuple[str, str], ...] = ()) -> GraspObject:
    """A rigid object from a user mesh (metres), centred on its bounding box, base on the floor.

    Mass from ``mass``, else ``density`` (default :data:`DEFAULT_MESH_DENSITY`) × the mesh's
    volume; inertia from the mesh (MuJoCo computes it from the same triangles); collision from
    its convex hull. The footprint checked against the aperture is the hull's horizontal radius
    about the centre. The defaults of the ``mesh:PATH`` shortcut (friction 0.6, a 200 N contact
    force limit, full closing) are the block's; an object file declares its own.
    """
    mesh = load_mesh(path)
    lo, hi = mesh.bounds
    hx, hy, hz = (float(v) for v in 0.5 * (hi - lo))
    centre = 0.5 * (lo + hi)
    hull = mesh.convex_hull.vertices - centre
    footprint = float(max(math.hypot(x, y) for x, y in hull[:, :2]))
    if mass is None:
        rho = DEFAULT_MESH_DENSITY if density is None else density
        if isinstance(rho, bool) or not (isinstance(rho, int | float) and math.isfinite(rho) and rho > 0):
            raise ValueError(f"mesh: density must be > 0 kg/m³, got {rho!r}")
        mass = rho * float(mesh.volume)
    obj = GraspObject(name=name or f"mesh:{path}", kind="mesh", size=(hx, hy, hz), mass=mass,
                      friction=friction, yaw_symmetric=yaw_symmetric, close_command=close_command,
                      damage=damage, damage_limit=damage_limit, mesh_file=str(path),
                      footprint_radius=footprint, reasons=reasons)
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
    import tempfile

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


# A zipper bag's contents lie in one layer on the bag's floor, in a grid, this far from the film
# and from each other [m] (the film's contact radius plus a margin).
ZIPPER_GAP = 0.002


def zipper_bag_layout(obj: GraspObject) -> list[tuple[float, float, float]]:
    """Centres of a zipper bag's items in the bag's frame [m]: one layer on its floor, a grid
    along the bag's length (x) and width (y), each item's long side along x.

    Raises:
        ValueError: no contents, items that do not fit in one layer, or contents heavier than
            the bag's total mass.
    """
    where = f"object.{obj.name}.contents"
    n = obj.contents_count
    if not (isinstance(n, int) and not isinstance(n, bool) and 1 <= n <= 64):
        raise ValueError(f"{where}.count: a zipper_bag holds 1 to 64 items, got {n!r}")
    hs = obj.contents_size
    if not (len(hs) == 3 and all(isinstance(v, int | float) and math.isfinite(v) and v > 0 for v in hs)):
        raise ValueError(f"{where}.size: three half-extents > 0 m, got {list(hs)!r}")
    m = obj.contents_mass
    if not (isinstance(m, int | float) and math.isfinite(m) and 0 < m and n * m < obj.mass):
        raise ValueError(f"{where}.mass: each item > 0 kg and all {n} lighter than the bag's total "
                         f"{obj.mass:g} kg (film included), got {m!r}")
    bx, by, bz = obj.size
    pitch_x, pitch_y = 2 * hs[0] + ZIPPER_GAP, 2 * hs[1] + ZIPPER_GAP
    nx = int((2 * bx - ZIPPER_GAP) // pitch_x)
    ny = int((2 * by - ZIPPER_GAP) // pitch_y)
    if nx * ny < n or 2 * hs[2] + 2 * ZIPPER_GAP > 2 * bz:
        raise ValueError(f"{where}: {n} items of {2e3 * hs[0]:.1f} x {2e3 * hs[1]:.1f} x {2e3 * hs[2]:.1f} mm "
                         f"do not lie in one layer inside {2e3 * bx:.0f} x {2e3 * by:.0f} x {2e3 * bz:.0f} mm")
    rows = math.ceil(n / nx)
    out = []
    for k in range(n):
        i, j = k % nx, k // nx
        cols = min(nx, n - j * nx)
        out.append(((i - 0.5 * (cols - 1)) * pitch_x, (j - 0.5 * (rows - 1)) * pitch_y,
                    -bz + ZIPPER_GAP + hs[2]))
    return out


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
