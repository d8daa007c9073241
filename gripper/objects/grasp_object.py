"""What a grasp object is: its kind, size, mass, friction, damage criterion and, for the
deformable kinds, material and mesh (SI units), validated once.

An object must fit the opening of the gripper that grasps it: its horizontal half-extent (its
half-diagonal where yaw is sampled) inside the open fingers' grasping faces, unless it is
marked oversize or is a long part whose half-width the wrist can straddle
(:meth:`GraspObject.check_fits`, with the design's opening from
``gripper.experiments.approach.check_fits_opening``).

Example:
    >>> from gripper.objects.library import get_object
    >>> get_object("balloon").kind
    'balloon'
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from gripper.core.fields import Validated, check_safe_name
from gripper.core.ranges import (
    CLOSE_COMMAND,
    FRICTION,
    OBJECT_HALF_EXTENT,
    OBJECT_MASS,
)
from gripper.objects.kinds import ObjectKind, object_kind, registered_kinds
from gripper.objects.kinds.base import MATERIAL_RANGES

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
        kind: the name of its registered kind (:mod:`gripper.objects.kinds`): ``rigid_box``,
            ``rigid_cylinder``, ``rigid_sphere``, ``mesh`` (rigid, from a user mesh), or a
            deformable one: ``balloon``, ``paper_box``, ``bag``, ``zipper_bag``.
        size: half-extents [m] (box: x, y, z; cylinder/balloon: radius, radius, half-height;
            sphere: radius three times).
        mass: total mass [kg].
        friction: sliding friction coefficient against the silicone pads [-].
        yaw_symmetric: True where yaw does not change the grasp (no yaw is sampled).
        close_command: the object's own closing command under the per-object policy, in the
            drive's command unit (a cable servo's spool angle [rad]).
        damage: the damage criterion, one its kind allows (``ObjectKind.criteria``): the
            built-in kinds have ``strain``, ``dent``, ``contact_force`` and ``none``.
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
            The deformables default to their kind's ``default_mesh_points`` (their convergence
            check is in ``docs/performance.md``).
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
    def object_kind(self) -> ObjectKind:
        """The registered kind this object is (what builds it, how it is damaged)."""
        return object_kind(self.kind)

    @property
    def half_width(self) -> float:
        """Largest horizontal distance of the object from its centre over all yaws [m]: the
        mesh hull's footprint radius, the box's half-diagonal (its corners sweep a circle when
        yaw is sampled), or the round objects' radius (its kind's ``half_width``)."""
        return self.object_kind.half_width(self)

    @property
    def is_flex(self) -> bool:
        """Whether the object is a deformable flex (its kind is)."""
        return self.object_kind.deformable

    @property
    def reads_strain(self) -> bool:
        """Whether its damage measure is the flex's peak edge strain, read at every step."""
        return self.object_kind.reads_strain

    @property
    def damage_measure(self) -> str:
        """What the damage criterion measures, with its unit."""
        return self.object_kind.criteria[self.damage].measure

    def is_damaged(self, measure: float) -> bool:
        """Whether ``measure`` (of :attr:`damage`) exceeds the limit; never for a criterion
        without a limit (``none``)."""
        return self.object_kind.criteria[self.damage].limit is not None and measure > self.damage_limit

    def validate(self) -> GraspObject:
        if isinstance(self.name, str) and self.name.startswith("mesh:"):
            _check_mesh_spec(self.name)
        else:
            check_safe_name(self.name, "object.name")
        where = f"object.{self.name}"
        try:
            kind = object_kind(self.kind)
        except ValueError as e:
            raise ValueError(f"{where}.kind: {e}") from None
        for i, s in enumerate(self.size):
            OBJECT_HALF_EXTENT.check(f"{where}.size[{i}]", s)
        OBJECT_MASS.check(f"{where}.mass", self.mass)
        FRICTION.check(f"{where}.friction", self.friction)
        CLOSE_COMMAND.check(f"{where}.close_command", self.close_command)
        if self.damage not in kind.criteria:
            raise ValueError(f"{where}.damage: a {self.kind} allows {', '.join(kind.criteria)}, got {self.damage!r}")
        limit = kind.criteria[self.damage].limit
        if limit is not None:
            limit.check(f"{where}.damage_limit", self.damage_limit)
        for key in kind.material_fields:
            MATERIAL_RANGES[key].check(f"{where}.{key}", getattr(self, key))
        pts = self.mesh_points
        if not (isinstance(pts, tuple) and len(pts) == 3
                and all(isinstance(n, int) and not isinstance(n, bool) for n in pts)):
            raise ValueError(f"{where}.mesh_points: must be three whole numbers, got {pts!r}")
        if not kind.deformable and pts != (0, 0, 0):
            raise ValueError(f"{where}.mesh_points: a {self.kind} is rigid and has no mesh resolution, "
                             f"got {list(pts)}")
        if self.contents_count and "contents" not in kind.file_tables:
            holders = [k.name for k in registered_kinds().values() if "contents" in k.file_tables]
            raise ValueError(f"{where}.contents: only a {' or '.join(holders)} holds loose contents, "
                             f"this is a {self.kind}")
        kind.check(self, where)
        return self

    def check_fits(self, opening: float, straddle_half_width: float) -> GraspObject:
        """Refuse an object the gripper cannot take: its horizontal footprint (over all yaws)
        wider than the open fingers' ``opening`` radius [m], unless it is marked oversize, or
        a long part no more than ``straddle_half_width`` [m] half-wide, which the wrist
        straddles (both from the design in use: ``gripper.experiments.approach.check_fits_opening``).
        Return ``self``."""
        straddled = min(self.size[0], self.size[1]) <= straddle_half_width
        if self.half_width > opening and not self.oversize and not straddled:
            what = "hull footprint radius" if self.footprint_radius > 0 else "horizontal half-extent"
            raise ValueError(f"object.{self.name}.size: its {what} is {self.half_width:.3f} m over all yaws and its "
                             f"half-width {min(self.size[0], self.size[1]):.3f} m; the open fingers of this design "
                             f"leave {opening:.3f} m, or straddle a part up to {straddle_half_width:.4f} m half-wide: "
                             "scale the object down (a round part: declare it yaw_symmetric, so its radius counts)")
        return self

    def to_dict(self) -> dict:
        """The physics of the object (everything but :attr:`reasons`; the contents only where
        there are some), JSON-ready."""
        skip = {"reasons"}
        if not self.contents_count:
            skip |= {"contents_count", "contents_size", "contents_mass"}
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name not in skip}
