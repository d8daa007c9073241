"""What a grasp object is: its kind, size, mass, friction, damage criterion and, for the
deformable kinds, material and mesh (SI units), validated once.

Every object is sized to the default gripper's aperture: with straight fingers the grasping
faces stand the palm radius from the palm axis, and an object's horizontal half-extent (its
half-diagonal where yaw is sampled) must fit inside, unless it is marked oversize or is a long
part whose half-width the wrist can straddle (:data:`STRADDLE_HALF_WIDTH`).

Example:
    >>> from gripper.objects.library import get_object
    >>> get_object("balloon").kind
    'balloon'
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from gripper.core.fields import Validated, check_safe_name
from gripper.core.params import FingerGeometry, GripperLayout
from gripper.core.ranges import (
    CLOSE_COMMAND,
    DAMAGE_LIMIT,
    FILM_THICKNESS,
    FRICTION,
    OBJECT_HALF_EXTENT,
    OBJECT_MASS,
    OBJECT_MODULUS,
    YIELD_STRAIN,
)

# Damage criteria: what is measured, its unit, and the kinds it applies to.
DAMAGE_CRITERIA = {
    "strain": ("peak edge strain of the membrane or film [-] (burst or tear above the limit)",
               ("balloon", "bag", "zipper_bag")),
    "dent": ("permanent dent depth after spring-back [m]", ("paper_box",)),
    "contact_force": ("peak total contact force [N]", ("rigid_box", "rigid_cylinder", "rigid_sphere", "mesh")),
    "none": ("not damaged by grasping", ("rigid_box", "rigid_cylinder", "rigid_sphere", "mesh")),
}
# The material fields each deformable kind is made of (the rigid kinds have none).
MATERIAL_NEEDS = {"balloon": ("youngs_modulus",), "bag": ("youngs_modulus", "thickness"),
                  "zipper_bag": ("youngs_modulus", "thickness"),
                  "paper_box": ("youngs_modulus", "thickness", "yield_strain")}
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
# The open fingers' grasping faces stand this far from the palm axis at their tips in the default
# design (gripper.experiments.approach.open_radius: the palm radius plus the splay of the fingers'
# length): an object's horizontal footprint must fit inside [m], or be straddled.
APERTURE_RADIUS = GripperLayout().palm_radius + FingerGeometry().length * math.sin(
    math.radians(GripperLayout().mount_tilt_deg))
# A longer part is straddled (gripper.experiments.approach): its long axis between two
# neighbouring fingers of the default design, so its half-width must stay this far inside their
# nearest corners, R sin 45° - (w/2) cos 45°, less the approach's 3 mm margin [m].
STRADDLE_HALF_WIDTH = (APERTURE_RADIUS - 0.5 * FingerGeometry().width) * math.sqrt(0.5) - 0.003


# A zipper bag's contents lie in one layer on the bag's floor, in a grid, this far from the film
# and from each other [m] (the film's contact radius plus a margin).
ZIPPER_GAP = 0.002


MESH_SPEC_MAX = 255  # characters of a ``mesh:PATH[::MASS]`` name, a file system's name limit


def _check_mesh_spec(spec: str) -> None:
    """A ``mesh:`` spec names its records: printable, one line, at most :data:`MESH_SPEC_MAX`."""
    if len(spec) > MESH_SPEC_MAX or not spec.isprintable():
        raise ValueError(f"objects: a mesh:PATH name must be printable and at most {MESH_SPEC_MAX} "
                         f"characters, got {len(spec)} characters")


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
            OBJECT_HALF_EXTENT.check(f"{where}.size[{i}]", s)
        OBJECT_MASS.check(f"{where}.mass", self.mass)
        FRICTION.check(f"{where}.friction", self.friction)
        CLOSE_COMMAND.check(f"{where}.close_command", self.close_command)
        if self.damage not in DAMAGE_CRITERIA or self.kind not in DAMAGE_CRITERIA[self.damage][1]:
            allowed = [c for c, (_, kinds) in DAMAGE_CRITERIA.items() if self.kind in kinds]
            raise ValueError(f"{where}.damage: a {self.kind} allows {', '.join(allowed)}, got {self.damage!r}")
        if self.damage != "none":
            DAMAGE_LIMIT[self.damage].check(f"{where}.damage_limit", self.damage_limit)
        for key, rng in (("youngs_modulus", OBJECT_MODULUS), ("thickness", FILM_THICKNESS),
                         ("yield_strain", YIELD_STRAIN)):
            if key in MATERIAL_NEEDS.get(self.kind, ()):
                rng.check(f"{where}.{key}", getattr(self, key))
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
        straddled = min(self.size[0], self.size[1]) <= STRADDLE_HALF_WIDTH
        if self.half_width > APERTURE_RADIUS and not self.oversize and not straddled:
            what = "hull footprint radius" if self.kind == "mesh" and self.footprint_radius > 0 else \
                "horizontal half-extent"
            raise ValueError(f"{where}.size: its {what} is {self.half_width:.3f} m over all yaws and its half-width "
                             f"{min(self.size[0], self.size[1]):.3f} m; the open fingers of the default design "
                             f"leave {APERTURE_RADIUS:.3f} m, or straddle a part up to {STRADDLE_HALF_WIDTH:.4f} m "
                             "half-wide: scale the object down (a round part: declare it yaw_symmetric, so its "
                             "radius counts)")
        return self

    def to_dict(self) -> dict:
        """The physics of the object (everything but :attr:`reasons`; the contents only where
        there are some), JSON-ready."""
        skip = {"reasons"}
        if not self.contents_count:
            skip |= {"contents_count", "contents_size", "contents_mass"}
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name not in skip}


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
    if len(hs) != 3:
        raise ValueError(f"{where}.size: three half-extents [m], got {list(hs)!r}")
    for i, v in enumerate(hs):
        OBJECT_HALF_EXTENT.check(f"{where}.size[{i}]", v)
    m = OBJECT_MASS.check(f"{where}.mass", obj.contents_mass)
    if not n * m < obj.mass:
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

