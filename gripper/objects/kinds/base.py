"""What an object kind is: one component that knows how to build its objects into a scene,
how they are damaged, whether they deform, their footprint, and which fields of an object file
they read. Kinds register by name (:func:`register_object_kind`); a
:class:`~gripper.objects.grasp_object.GraspObject` names its kind and asks it.

This module imports nothing of the objects it serves, so that every layer can look a kind up
without an import cycle: objects are typed loosely here (``obj``: a ``GraspObject``).

Example:
    >>> from gripper.objects.kinds import object_kind
    >>> object_kind("balloon").deformable, object_kind("rigid_box").deformable
    (True, False)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol

import mujoco

from gripper.core.ranges import DAMAGE_LIMIT, FILM_THICKNESS, OBJECT_MODULUS, YIELD_STRAIN, Range

OBJECT_BODY = "object"  # the object's body (rigid kinds) or flex (deformable kinds)
CONTENTS_BODY = "object_contents"  # the body, or prefix of the bodies, of what a bag holds

# The rigid kinds' closing command: near the end of the servo's travel (π) and past full finger
# closure (≈ 2.3 rad), so the drive stalls on the part and squeezes with its stall effort
# (gripper/data/objects/block.toml gives the reason); user meshes default to it.
RIGID_CLOSE = 3.0


@dataclass(frozen=True)
class Criterion:
    """A damage criterion: what it measures, with its unit, and the allowed range of its limit
    (None: the criterion has no limit)."""

    measure: str
    limit: Range | None


# The material fields a kind may need (ObjectKind.material_fields: GraspObject fields), with
# their ranges.
MATERIAL_RANGES = {"youngs_modulus": OBJECT_MODULUS, "thickness": FILM_THICKNESS, "yield_strain": YIELD_STRAIN}

CONTACT_FORCE = Criterion("peak total contact force [N]", DAMAGE_LIMIT["contact_force"])
NOT_DAMAGED = Criterion("not damaged by grasping", None)
EDGE_STRAIN = Criterion("peak edge strain of the membrane or film [-] (burst or tear above the limit)",
                        DAMAGE_LIMIT["strain"])
PERMANENT_DENT = Criterion("permanent dent depth after spring-back [m]", DAMAGE_LIMIT["dent"])


class Placed(Protocol):
    """Where a trial puts the object (``gripper.objects.scene_objects.Placement``): its
    offset [m], yaw [rad], and the scales of its mass and friction [-]."""

    @property
    def x(self) -> float: ...
    @property
    def y(self) -> float: ...
    @property
    def yaw(self) -> float: ...
    @property
    def mass_scale(self) -> float: ...
    @property
    def friction_scale(self) -> float: ...


def object_friction(obj: Any, place: Placed) -> list[float]:
    """MuJoCo's (sliding, torsional, rolling) friction of the object at ``place``: the
    silicone-object pair's sliding coefficient, scaled as the trial samples it."""
    return [obj.friction * place.friction_scale, 0.005, 1e-4]


class ObjectKind:
    """One kind of grasp object. Subclass, set the class attributes, implement :meth:`build`
    (and what differs from the defaults), and register an instance with
    :func:`register_object_kind`; ``docs/architecture.md`` ("Add an object kind") walks
    through it.

    Attributes:
        name: the kind's name, as object files and ``GraspObject.kind`` give it.
        deformable: a MuJoCo flex named :data:`OBJECT_BODY` (True) or rigid bodies.
        criteria: the damage criteria an object of this kind may declare.
        own_criterion: the criterion an object file may leave out (None: it must declare one).
        material_fields: the ``[material]`` fields the kind needs (``GraspObject`` fields).
        default_mesh_points: a deformable kind's default mesh resolution (x, y, z points).
        yaw_symmetric: whether its objects are yaw-symmetric unless a file says otherwise.
        square_footprint: its footprint has corners (a box), not a round outline.
        tracked_body: the body whose origin is the object's position; None: the flex's centroid.
        reads_strain: its damage measure is the flex's peak edge strain, read at every step.
        history_dependent: its compiled constants depend on the process's history (an
            interpolated flex): trials compile it canonically (``gripper.sim.canonical``).
        file_tables: the object-file tables this kind reads beyond the common ones, with
            their keys (read by :meth:`read_tables`).
        sized_by_mesh: an object file gives its mesh (``object.mesh``), not its size.
    """

    name: ClassVar[str] = ""
    deformable: ClassVar[bool] = False
    criteria: ClassVar[dict[str, Criterion]] = {"contact_force": CONTACT_FORCE, "none": NOT_DAMAGED}
    own_criterion: ClassVar[str | None] = None
    material_fields: ClassVar[tuple[str, ...]] = ()
    default_mesh_points: ClassVar[tuple[int, int, int]] = (0, 0, 0)
    yaw_symmetric: ClassVar[bool] = False
    square_footprint: ClassVar[bool] = False
    tracked_body: ClassVar[str | None] = OBJECT_BODY
    reads_strain: ClassVar[bool] = False
    history_dependent: ClassVar[bool] = False
    file_tables: ClassVar[dict[str, tuple[str, ...]]] = {}
    sized_by_mesh: ClassVar[bool] = False

    # -- shape ----------------------------------------------------------------------------
    def half_width(self, obj: Any) -> float:
        """Largest horizontal distance of the object from its centre over all yaws [m]: a
        square footprint's half-diagonal where yaw is sampled (its corners sweep a circle), else
        the larger horizontal half-extent (a round footprint's radius)."""
        if self.square_footprint and not obj.yaw_symmetric:
            return math.hypot(obj.size[0], obj.size[1])
        return max(obj.size[0], obj.size[1])

    def volume(self, size: tuple[float, float, float]) -> float | None:
        """The solid's volume from its half-extents [m³], for a mass from a density; None: the
        kind takes a mass, not a density."""
        return None

    # -- checks and files -----------------------------------------------------------------
    def check(self, obj: Any, where: str) -> None:
        """The kind's own rules on an object (``where`` prefixes the error); raise ValueError."""

    def read_tables(self, tables: dict[str, dict], read: Any, fail: Any) -> dict[str, Any]:
        """``GraspObject`` keyword arguments from the kind's :attr:`file_tables` (``read(table,
        section, key, type, default=None, required=False)`` reads and checks one value,
        ``fail(key, message)`` makes the error)."""
        return {}

    # -- the scene ------------------------------------------------------------------------
    def build(self, spec: mujoco.MjSpec, obj: Any, place: Placed, pos: list[float], quat: list[float], *,
              rigid_contact: bool) -> None:
        """Add ``obj`` to ``spec`` at ``pos`` and ``quat`` (its centre), scaled by ``place``'s
        mass and friction scales; ``rigid_contact``: a rigid part's contacts near-rigid."""
        raise NotImplementedError

    # -- damage ---------------------------------------------------------------------------
    def damage_measure(self, m: mujoco.MjModel, d: mujoco.MjData, obj: Any, probe: Any, *,
                       peak_strain: float, peak_force: float) -> float:
        """The trial's damage measure at its end (the state in ``d``): the peak edge strain
        where :attr:`reads_strain`, else the peak total contact force [N]."""
        return peak_strain if self.reads_strain else peak_force

    def running_damage(self, m: mujoco.MjModel, d: mujoco.MjData, obj: Any, probe: Any, *,
                       peak_strain: float, total_force: float) -> float:
        """The damage measure where it must be read at every step (the environment): as
        :meth:`damage_measure` unless the kind needs a slower reading at the end."""
        return peak_strain if self.reads_strain else total_force


_KINDS: dict[str, ObjectKind] = {}


def register_object_kind(kind: ObjectKind) -> ObjectKind:
    """Make ``kind`` known by its name (a name registered again is replaced); return it."""
    if not isinstance(kind, ObjectKind) or not kind.name.isidentifier():
        raise ValueError(f"object kind: an ObjectKind instance with an identifier name, got {kind!r}")
    if not kind.criteria:
        raise ValueError(f"object kind {kind.name}: declares no damage criterion")
    unknown = [f for f in kind.material_fields if f not in MATERIAL_RANGES]
    if unknown:
        raise ValueError(f"object kind {kind.name}: material fields {', '.join(unknown)} unknown; "
                         f"allowed: {', '.join(MATERIAL_RANGES)}")
    if kind.own_criterion is not None and kind.own_criterion not in kind.criteria:
        raise ValueError(f"object kind {kind.name}: own_criterion {kind.own_criterion!r} is not one of its criteria")
    _KINDS[kind.name] = kind
    return kind


def unregister_object_kind(name: str) -> None:
    """Forget a kind (a test's own kind, once it is done)."""
    _KINDS.pop(name, None)


def registered_kinds() -> dict[str, ObjectKind]:
    """The kinds known now, by name (the built-in ones from :mod:`gripper.objects.kinds`)."""
    return _KINDS
